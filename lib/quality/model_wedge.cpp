#include "quality/model_wedge.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace polydual {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Solid angle at a of the tet (a, b, c, d) (Van Oosterom and Strackee, 1983).
double solid_angle(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const Vec3 x = b - a, y = c - a, z = d - a;
  const double lx = norm(x), ly = norm(y), lz = norm(z);
  const double num = std::fabs(dot(x, cross(y, z)));
  const double den = lx * ly * lz + dot(x, y) * lz + dot(x, z) * ly + dot(y, z) * lx;
  double omega = 2.0 * std::atan2(num, den);
  if (omega < 0) omega += 2.0 * kPi;
  return omega;
}

// Interior dihedral angle of a tet at its edge (p, q), the other two vertices r, s, radians.
double dihedral(const Point3& p, const Point3& q, const Point3& r, const Point3& s) {
  const Vec3 e = q - p;
  const double ee = dot(e, e);
  const Vec3 u = (r - p) - (dot(r - p, e) / ee) * e;
  const Vec3 w = (s - p) - (dot(s - p, e) / ee) * e;
  const double c = dot(u, w) / (norm(u) * norm(w));
  return std::acos(std::clamp(c, -1.0, 1.0));
}

}  // namespace

VertexWedge vertex_wedge(const ClassifiedTetMesh& m, VertexId v, std::int32_t material) {
  VertexWedge w;
  std::vector<std::pair<std::uint32_t, double>> at_edges;  // (edge, dihedral) per tet
  for (TetId t : m.vertex_tets(v)) {
    if (m.region(t) != material) continue;
    const auto& tv = m.tet(t);
    const int li = m.local_index(t, v);
    w.solid_angle_sr += solid_angle(m.point(tv[li]), m.point(tv[(li + 1) % 4]), m.point(tv[(li + 2) % 4]),
                                    m.point(tv[(li + 3) % 4]));
    for (int k = 0; k < 6; ++k) {
      const int a = kTetEdge[k][0], b = kTetEdge[k][1];
      if (a != li && b != li) continue;
      const EdgeId e = m.tet_edge(t, k);
      if (m.edge_class(e).dim != 1) continue;
      const int o = a == li ? b : a;
      int r = -1, s = -1;
      for (int i = 0; i < 4; ++i)
        if (i != li && i != o) (r < 0 ? r : s) = i;
      at_edges.push_back({e.idx, dihedral(m.point(tv[li]), m.point(tv[o]), m.point(tv[r]), m.point(tv[s]))});
    }
  }
  std::sort(at_edges.begin(), at_edges.end());
  for (std::size_t i = 0; i < at_edges.size();) {
    double sum = 0;
    std::size_t j = i;
    for (; j < at_edges.size() && at_edges[j].first == at_edges[i].first; ++j) sum += at_edges[j].second;
    const double deg = sum * 180.0 / kPi;
    if (deg < w.min_wedge_deg) {
      w.min_wedge_deg = deg;
      w.wedge_edge = m.edge_class(EdgeId(at_edges[i].first));
    }
    i = j;
  }
  return w;
}

}  // namespace polydual
