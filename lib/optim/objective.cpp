#include "optim/objective.h"

#include <stdexcept>

namespace polydual {

double cell_energy_gradient(const MeshStencil& s, std::uint32_t c, Metric m,
                            std::span<const Point3> pts, double V0, double c_delta, Vec3* grad,
                            Vec3* grad_R, Vec3* grad_F) {
  if (grad && s.loop_local.size() != s.loop_pts.size())
    throw std::logic_error("cell_energy_gradient: per-point gradients need build_stencil(mesh, true)");
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
    const std::uint32_t* ll = grad ? s.loop_local.data() + b0 : nullptr;  // empty unless built for grad
    Vec3 F{}, gF{}, g1, g2, g3;
    for (std::uint32_t i = 0; i < k; ++i) F += pts[lp[i].idx];
    F = F / static_cast<double>(k);
    for (std::uint32_t i = 0; i < k; ++i) {
      if (m == Metric::Q1) {
        // Edge (a,b) = (loop[i-1], loop[i]); corners at a and b of tet (a,b,F,R).
        const std::uint32_t ia = (i + k - 1) % k, ib = i;
        const Point3 &a = pts[lp[ia].idx], &b = pts[lp[ib].idx];
        energy += corner_kappa_mod_gradient(F - a, b - a, R - a, V0, c_delta, g1, g2, g3);
        gF += g1; gR += g3;
        if (grad) {
          grad[ll[ib]] += g2;
          grad[ll[ia]] -= g1 + g2 + g3;
        }
        energy += corner_kappa_mod_gradient(a - b, F - b, R - b, V0, c_delta, g1, g2, g3);
        gF += g2; gR += g3;
        if (grad) {
          grad[ll[ia]] += g1;
          grad[ll[ib]] -= g1 + g2 + g3;
        }
      } else {
        const std::uint32_t ip = (i + k - 1) % k, in = (i + 1) % k;
        const Point3 &p = pts[lp[ip].idx], &v = pts[lp[i].idx], &n = pts[lp[in].idx];
        energy += corner_kappa_mod_gradient(p - v, n - v, R - v, V0, c_delta, g1, g2, g3);
        gR += g3;
        if (grad) {
          grad[ll[ip]] += g1; grad[ll[in]] += g2;
          grad[ll[i]] -= g1 + g2 + g3;
        }
      }
    }
    if (grad_F) grad_F[j - s.cell_loop_off[c]] = gF;
    if (grad) {
      const Vec3 share = gF / static_cast<double>(k);
      for (std::uint32_t i = 0; i < k; ++i) grad[ll[i]] += share;
    }
  }
  if (grad_R) *grad_R = gR;
  if (grad) {
    const Vec3 share = gR / static_cast<double>(np);
    for (std::size_t i = 0; i < np; ++i) grad[i] += share;
  }
  return energy;
}

double local_objective_derivatives(const MeshStencil& s, const Point3* pts, const double* V0, Metric m,
                                   double c_delta, PointId p, double g[3], double H[9]) {
  for (int i = 0; i < 3; ++i) g[i] = 0;
  for (int i = 0; i < 9; ++i) H[i] = 0;
  double sum = 0.0;
  // Same arithmetic as for_each_corner<double> (stencil.h), so the value matches
  // LocalObjective bit for bit; the weights are d e / d x_p (scalars).
  for (std::uint32_t cell : s.cells_of(p)) {
    const double v0 = V0[cell];
    double R[3];
    const double wR = mean_of(s.points_of(cell), pts, R);
    // Corners that see p only through R: derivatives in e3 summed per cell, then
    // scaled once by wR (gradient) and wR^2 (Hessian).
    double gR[3] = {0.0, 0.0, 0.0}, HR[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    double e1[3], e2[3], e3[3];
    for (std::uint32_t j = s.cell_loop_off[cell]; j < s.cell_loop_off[cell + 1]; ++j) {
      const auto loop = s.loop(j);
      const std::size_t k = loop.size();
      if (m == Metric::Q1) {
        double F[3] = {0.0, 0.0, 0.0};
        bool has_p = false;
        for (PointId q : loop) {
          const Point3& y = pts[q.idx];
          F[0] += y.x; F[1] += y.y; F[2] += y.z;
          has_p = has_p || q == p;
        }
        const double inv_k = 1.0 / static_cast<double>(k);
        F[0] *= inv_k; F[1] *= inv_k; F[2] *= inv_k;
        const double wF = has_p ? inv_k : 0.0;
        PointId qa = loop[k - 1];
        for (std::size_t i = 0; i < k; ++i) {
          const PointId qb = loop[i];
          const Point3 &a = pts[qa.idx], &b = pts[qb.idx];
          const double ia = qa == p ? 1.0 : 0.0, ib = qb == p ? 1.0 : 0.0;
          for (int d = 0; d < 3; ++d) { e1[d] = F[d] - a[d]; e2[d] = b[d] - a[d]; e3[d] = R[d] - a[d]; }
          sum += has_p ? corner_kappa_mod_add_point_derivatives(e1, e2, e3, wF - ia, ib - ia, wR - ia, v0, c_delta, g, H)
                       : corner_kappa_mod_add_e3_derivatives(e1, e2, e3, 1.0, v0, c_delta, gR, HR);
          for (int d = 0; d < 3; ++d) { e1[d] = a[d] - b[d]; e2[d] = F[d] - b[d]; e3[d] = R[d] - b[d]; }
          sum += has_p ? corner_kappa_mod_add_point_derivatives(e1, e2, e3, ia - ib, wF - ib, wR - ib, v0, c_delta, g, H)
                       : corner_kappa_mod_add_e3_derivatives(e1, e2, e3, 1.0, v0, c_delta, gR, HR);
          qa = qb;
        }
      } else {
        for (std::size_t i = 0; i < k; ++i) {
          const PointId qp = loop[(i + k - 1) % k], qv = loop[i], qn = loop[(i + 1) % k];
          const Point3 &pp = pts[qp.idx], &v = pts[qv.idx], &n = pts[qn.idx];
          const double ip = qp == p ? 1.0 : 0.0, iv = qv == p ? 1.0 : 0.0, in = qn == p ? 1.0 : 0.0;
          for (int d = 0; d < 3; ++d) { e1[d] = pp[d] - v[d]; e2[d] = n[d] - v[d]; e3[d] = R[d] - v[d]; }
          sum += (ip != 0 || iv != 0 || in != 0)
                     ? corner_kappa_mod_add_point_derivatives(e1, e2, e3, ip - iv, in - iv, wR - iv, v0, c_delta, g, H)
                     : corner_kappa_mod_add_e3_derivatives(e1, e2, e3, 1.0, v0, c_delta, gR, HR);
        }
      }
    }
    for (int i = 0; i < 3; ++i) g[i] += wR * gR[i];
    for (int i = 0; i < 9; ++i) H[i] += (wR * wR) * HR[i];
  }
  return sum;
}

}  // namespace polydual
