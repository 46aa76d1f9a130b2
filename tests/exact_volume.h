// Exact per-material volumes (x6, CGAL rationals) of a dual and of its primal,
// shared by the tests (dual, split, classification): on a planar-faced domain whose model edges and
// vertices were all found, the dual covers each material exactly.
#pragma once
#include <CGAL/Gmpq.h>

#include <cstdint>
#include <map>

#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"

namespace polydual::testing {

using Q = CGAL::Gmpq;
struct QPoint { Q x, y, z; };

inline Q det3(const QPoint& a, const QPoint& b, const QPoint& c) {
  return a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
}
inline QPoint minus(const QPoint& a, const QPoint& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline QPoint exact(const Point3& p) { return {Q(p.x), Q(p.y), Q(p.z)}; }

// Sum over each cell of the tets (R, a, b, F): R the mean of the cell's
// points, F the mean of the face's, (a, b) the face's edges in the cell's
// outward order (design §5), in exact rationals.
inline std::map<std::int32_t, Q> exact_dual_volumes(const PolyMesh& pm) {
  auto mean = [&](const auto& pts) {
    QPoint s{Q(0), Q(0), Q(0)};
    for (PointId p : pts) {
      const QPoint q = exact(pm.points[p.idx]);
      s = {s.x + q.x, s.y + q.y, s.z + q.z};
    }
    const Q n(int(pts.size()));
    return QPoint{s.x / n, s.y / n, s.z / n};
  };
  std::map<std::int32_t, Q> vol;
  for (std::size_t c = 0; c < pm.num_cells(); ++c) {
    const QPoint R = mean(pm.cell_points(CellId(c)));
    Q sum(0);
    for (HalfFace h : pm.cell(CellId(c))) {
      const auto loop = pm.oriented_loop(h);
      const QPoint F = mean(loop);
      for (std::size_t k = 0; k < loop.size(); ++k)
        sum += det3(minus(exact(pm.points[loop[k].idx]), R), minus(exact(pm.points[loop[(k + 1) % loop.size()].idx]), R),
                    minus(F, R));
    }
    vol[pm.cell_material[c]] += sum;
  }
  return vol;
}

inline std::map<std::int32_t, Q> exact_primal_volumes(const ClassifiedTetMesh& m) {
  std::map<std::int32_t, Q> vol;
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const auto& v = m.tet(TetId(t));
    const QPoint p0 = exact(m.point(v[0]));
    vol[m.region(TetId(t))] += det3(minus(exact(m.point(v[1])), p0), minus(exact(m.point(v[2])), p0),
                                    minus(exact(m.point(v[3])), p0));
  }
  return vol;
}

}  // namespace polydual::testing
