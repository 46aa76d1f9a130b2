#include "optim/lagged_objective.h"

namespace polydual {

void LaggedObjective::add(const Point3* P, const bool* is_p, const Point3& vertex, bool vertex_is_p, double v0) {
  // Corner at `vertex` with edges P_i - vertex; p enters with +1 as P_i and
  // with -1 as the vertex.
  Corner c;
  c.v0 = v0;
  for (int i = 0; i < 3; ++i) {
    c.a[i] = (is_p[i] ? 1.0 : 0.0) - (vertex_is_p ? 1.0 : 0.0);
    const Point3 pi = is_p[i] ? Point3{0, 0, 0} : P[i];
    const Point3 v = vertex_is_p ? Point3{0, 0, 0} : vertex;
    c.u[i] = Point3{pi.x - v.x, pi.y - v.y, pi.z - v.z};
  }
  corners_.push_back(c);
}

void LaggedObjective::build(const MeshStencil& s, const Point3* pts, const double* V0, Metric m, PointId p,
                            const Vec3* grad_R, const Vec3* grad_F) {
  corners_.clear();
  G_ = Vec3{};
  x0_ = pts[p.idx];
  for (std::uint32_t cell : s.cells_of(p)) {
    const auto cp = s.points_of(cell);
    Point3 R{0, 0, 0};
    for (PointId q : cp) R += pts[q.idx];
    const double inv_m = 1.0 / static_cast<double>(cp.size());  // as for_each_corner
    R = Point3{R.x * inv_m, R.y * inv_m, R.z * inv_m};
    if (grad_R) G_ += inv_m * grad_R[cell];
    for (std::uint32_t j = s.cell_loop_off[cell]; j < s.cell_loop_off[cell + 1]; ++j) {
      const auto loop = s.loop(j);
      const std::size_t k = loop.size();
      std::size_t at = k;
      for (std::size_t i = 0; i < k; ++i)
        if (loop[i] == p) at = i;
      if (at == k) continue;
      if (grad_F && m == Metric::Q1) G_ += grad_F[j] / static_cast<double>(k);
      const PointId prev = loop[(at + k - 1) % k], next = loop[(at + 1) % k];
      if (m == Metric::Q1) {
        Point3 F{0, 0, 0};
        for (PointId q : loop) F += pts[q.idx];
        const double inv_k = 1.0 / static_cast<double>(k);
        F = Point3{F.x * inv_k, F.y * inv_k, F.z * inv_k};
        // Edges (prev, p) and (p, next); tet (a, b, F, R): corners
        // (F-a, b-a, R-a) at a and (a-b, F-b, R-b) at b.
        for (int e = 0; e < 2; ++e) {
          const PointId a = e == 0 ? prev : p, b = e == 0 ? p : next;
          const Point3 &pa = pts[a.idx], &pb = pts[b.idx];
          {
            const Point3 P[3] = {F, pb, R};
            const bool ip[3] = {false, b == p, false};
            add(P, ip, pa, a == p, V0[cell]);
          }
          {
            const Point3 P[3] = {pa, F, R};
            const bool ip[3] = {a == p, false, false};
            add(P, ip, pb, b == p, V0[cell]);
          }
        }
      } else {
        // Corners (prev(v)-v, next(v)-v, R-v) at v = prev, p, next.
        for (int o = -1; o <= 1; ++o) {
          const std::size_t iv = (at + k + static_cast<std::size_t>(o + 1) - 1) % k;
          const PointId v = loop[iv], vp = loop[(iv + k - 1) % k], vn = loop[(iv + 1) % k];
          const Point3 P[3] = {pts[vp.idx], pts[vn.idx], R};
          const bool ip[3] = {vp == p, vn == p, false};
          add(P, ip, pts[v.idx], v == p, V0[cell]);
        }
      }
    }
  }
}

// The corner's three edge vectors with the point at x: u_i + a_i x.
void LaggedObjective::corner_edges(const Corner& k, const Point3& x, double e[3][3]) {
  for (int i = 0; i < 3; ++i) {
    e[i][0] = k.u[i].x + k.a[i] * x.x;
    e[i][1] = k.u[i].y + k.a[i] * x.y;
    e[i][2] = k.u[i].z + k.a[i] * x.z;
  }
}

double LaggedObjective::value(const Point3& x, double c) const {
  double sum = 0;
  double e[3][3];
  for (const Corner& k : corners_) {
    corner_edges(k, x, e);
    sum += corner_kappa_mod<double>(e[0], e[1], e[2], k.v0, c);
  }
  return sum + correction(x);
}

double LaggedObjective::derivatives(const Point3& x, double c, double g[3], double H[9]) const {
  for (int i = 0; i < 3; ++i) g[i] = 0;
  for (int i = 0; i < 9; ++i) H[i] = 0;
  double sum = 0;
  double e[3][3];
  for (const Corner& k : corners_) {
    corner_edges(k, x, e);
    sum += corner_kappa_mod_add_point_derivatives(e[0], e[1], e[2], k.a[0], k.a[1], k.a[2], k.v0, c, g, H);
  }
  g[0] += G_.x; g[1] += G_.y; g[2] += G_.z;
  return sum + correction(x);
}

}  // namespace polydual
