// Flat, precomputed cell topology for the quality metrics, the star test and the
// optimisers: per cell its distinct points and its face loops in the cell's
// outward order; per point its incident cells. Built once per run so inner loops
// never call PolyMesh::oriented_loop / cell_points (which allocate).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "mesh/poly_mesh.h"

namespace polydual {

// Q1 = symmetric decomposition corners, Q2 = region-centre corners (design §6).
enum class Metric : std::uint8_t { Q1 = 1, Q2 = 2 };

struct MeshStencil {
  // Cell c's distinct points: cell_pts[cell_pt_off[c] .. cell_pt_off[c+1]).
  std::vector<std::uint32_t> cell_pt_off{0};
  std::vector<PointId> cell_pts;
  // Cell c's loops are loops [cell_loop_off[c], cell_loop_off[c+1]); loop j is
  // loop_pts[loop_off[j] .. loop_off[j+1]), oriented outward of c.
  std::vector<std::uint32_t> cell_loop_off{0};
  std::vector<std::uint32_t> loop_off{0};
  std::vector<PointId> loop_pts;
  // loop_local[i]: index of loop_pts[i] within its cell's points_of() list
  // (built on request only: the per-point gradients of the global scheme).
  std::vector<std::uint32_t> loop_local;
  // Point p's cells: point_cells[point_cell_off[p] .. point_cell_off[p+1]), increasing.
  std::vector<std::uint32_t> point_cell_off;
  std::vector<std::uint32_t> point_cells;

  std::size_t num_cells() const { return cell_pt_off.size() - 1; }
  std::span<const PointId> points_of(std::uint32_t c) const {
    return {cell_pts.data() + cell_pt_off[c], cell_pts.data() + cell_pt_off[c + 1]};
  }
  std::span<const PointId> loop(std::uint32_t j) const {
    return {loop_pts.data() + loop_off[j], loop_pts.data() + loop_off[j + 1]};
  }
  std::span<const std::uint32_t> cells_of(PointId p) const {
    return {point_cells.data() + point_cell_off[p.idx],
            point_cells.data() + point_cell_off[p.idx + 1]};
  }
  // Number of corners of cell c for a metric: Q1 two per loop edge, Q2 one per loop vertex.
  std::size_t num_corners(std::uint32_t c, Metric m) const {
    const std::size_t n = loop_off[cell_loop_off[c + 1]] - loop_off[cell_loop_off[c]];
    return m == Metric::Q1 ? 2 * n : n;
  }
};

// local_indices: also fill loop_local (else it stays empty).
MeshStencil build_stencil(const PolyMesh& mesh, bool local_indices = false);

// The mean of the listed points into out (summed in list order, then scaled
// by 1/n: for_each_corner's R and F, bit for bit); returns 1/n.
inline double mean_of(std::span<const PointId> ids, const Point3* points, double out[3]) {
  out[0] = out[1] = out[2] = 0.0;
  for (PointId q : ids) {
    const Point3& x = points[q.idx];
    out[0] += x.x; out[1] += x.y; out[2] += x.z;
  }
  const double inv = 1.0 / static_cast<double>(ids.size());
  out[0] *= inv; out[1] *= inv; out[2] *= inv;
  return inv;
}

// Calls fn(e1, e2, e3) (arrays of 3 T, right-handed for a valid corner) for every
// corner of cell c under metric m. pos(PointId, T out[3]) supplies coordinates, so
// callers can make one point a ceres::Jet.
//  Q1: for each loop edge (a,b), tet (a,b,F,R): corner at a = (F-a, b-a, R-a),
//      corner at b = (a-b, F-b, R-b); V = 6 vol(R,a,b,F) > 0 iff the decomposition
//      tet is valid (design §5), so a positive Q1 corner is a valid star tet.
//  Q2: for each loop vertex v (prev p, next n): corner (p-v, n-v, R-v).
template <class T, class Pos, class Fn>
void for_each_corner(const MeshStencil& s, std::uint32_t c, Metric m, const Pos& pos, Fn&& fn) {
  T R[3] = {T(0.0), T(0.0), T(0.0)};
  T x[3];
  const auto pts = s.points_of(c);
  for (PointId q : pts) {
    pos(q, x);
    R[0] += x[0]; R[1] += x[1]; R[2] += x[2];
  }
  const double inv_m = 1.0 / static_cast<double>(pts.size());
  R[0] *= inv_m; R[1] *= inv_m; R[2] *= inv_m;
  T e1[3], e2[3], e3[3];
  for (std::uint32_t j = s.cell_loop_off[c]; j < s.cell_loop_off[c + 1]; ++j) {
    const auto loop = s.loop(j);
    const std::size_t k = loop.size();
    if (m == Metric::Q1) {
      T F[3] = {T(0.0), T(0.0), T(0.0)};
      for (PointId q : loop) {
        pos(q, x);
        F[0] += x[0]; F[1] += x[1]; F[2] += x[2];
      }
      const double inv_k = 1.0 / static_cast<double>(k);
      F[0] *= inv_k; F[1] *= inv_k; F[2] *= inv_k;
      T a[3], b[3];
      pos(loop[k - 1], a);
      for (std::size_t i = 0; i < k; ++i) {
        pos(loop[i], b);
        for (int d = 0; d < 3; ++d) { e1[d] = F[d] - a[d]; e2[d] = b[d] - a[d]; e3[d] = R[d] - a[d]; }
        fn(e1, e2, e3);
        for (int d = 0; d < 3; ++d) { e1[d] = a[d] - b[d]; e2[d] = F[d] - b[d]; e3[d] = R[d] - b[d]; }
        fn(e1, e2, e3);
        for (int d = 0; d < 3; ++d) a[d] = b[d];
      }
    } else {
      T p[3], v[3], n[3];
      pos(loop[k - 1], p);
      pos(loop[0], v);
      for (std::size_t i = 0; i < k; ++i) {
        pos(loop[(i + 1) % k], n);
        for (int d = 0; d < 3; ++d) { e1[d] = p[d] - v[d]; e2[d] = n[d] - v[d]; e3[d] = R[d] - v[d]; }
        fn(e1, e2, e3);
        for (int d = 0; d < 3; ++d) { p[d] = v[d]; v[d] = n[d]; }
      }
    }
  }
}

// Plain-double coordinate accessor over a point array.
struct PointsPos {
  const Point3* p;
  void operator()(PointId q, double out[3]) const {
    const Point3& x = p[q.idx];
    out[0] = x.x; out[1] = x.y; out[2] = x.z;
  }
};

}  // namespace polydual
