#include "optim/objective.h"

namespace polydual {

double cell_energy_gradient(const MeshStencil& s, std::uint32_t c, Metric m,
                            std::span<const Point3> pts, double V0, double c_delta, Vec3* grad) {
  const auto cp = s.points_of(c);
  const std::size_t np = cp.size();
  Vec3 R{};
  for (PointId q : cp) R += pts[q.idx];
  R = R / static_cast<double>(np);
  if (grad)
    for (std::size_t i = 0; i < np; ++i) grad[i] = Vec3{};
  Vec3 gR{};
  double energy = 0;
  for (std::uint32_t j = s.cell_loop_off[c]; j < s.cell_loop_off[c + 1]; ++j) {
    const std::uint32_t b0 = s.loop_off[j], k = s.loop_off[j + 1] - b0;
    const PointId* lp = s.loop_pts.data() + b0;
    const std::uint32_t* ll = s.loop_local.data() + b0;
    Vec3 F{}, gF{}, g1, g2, g3;
    for (std::uint32_t i = 0; i < k; ++i) F += pts[lp[i].idx];
    F = F / static_cast<double>(k);
    for (std::uint32_t i = 0; i < k; ++i) {
      if (m == Metric::Q1) {
        // Edge (a,b) = (loop[i-1], loop[i]); corners at a and b of tet (a,b,F,R).
        const std::uint32_t ia = (i + k - 1) % k, ib = i;
        const Point3 &a = pts[lp[ia].idx], &b = pts[lp[ib].idx];
        energy += corner_kappa_mod_gradient(F - a, b - a, R - a, V0, c_delta, g1, g2, g3);
        if (grad) {
          gF += g1; grad[ll[ib]] += g2; gR += g3;
          grad[ll[ia]] -= g1 + g2 + g3;
        }
        energy += corner_kappa_mod_gradient(a - b, F - b, R - b, V0, c_delta, g1, g2, g3);
        if (grad) {
          grad[ll[ia]] += g1; gF += g2; gR += g3;
          grad[ll[ib]] -= g1 + g2 + g3;
        }
      } else {
        const std::uint32_t ip = (i + k - 1) % k, in = (i + 1) % k;
        const Point3 &p = pts[lp[ip].idx], &v = pts[lp[i].idx], &n = pts[lp[in].idx];
        energy += corner_kappa_mod_gradient(p - v, n - v, R - v, V0, c_delta, g1, g2, g3);
        if (grad) {
          grad[ll[ip]] += g1; grad[ll[in]] += g2; gR += g3;
          grad[ll[i]] -= g1 + g2 + g3;
        }
      }
    }
    if (grad) {
      const Vec3 share = gF / static_cast<double>(k);
      for (std::uint32_t i = 0; i < k; ++i) grad[ll[i]] += share;
    }
  }
  if (grad) {
    const Vec3 share = gR / static_cast<double>(np);
    for (std::size_t i = 0; i < np; ++i) grad[i] += share;
  }
  return energy;
}

}  // namespace polydual
