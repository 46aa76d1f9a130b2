// Second-order derivatives of one corner's kappa_mod with respect to one mesh
// point (the analytic Newton model of the local scheme, SPEC §7; derivation in
// proofs/quality.md §6).
#include <cmath>

#include "quality/corner.h"

namespace polydual {
namespace {

// H += s (u v^T + v u^T)
inline void add_sym(double H[9], double s, const Vec3& u, const Vec3& v) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H[3 * i + j] += s * (u[i] * v[j] + v[i] * u[j]);
}
// H += s u u^T
inline void add_outer(double H[9], double s, const Vec3& u) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H[3 * i + j] += s * u[i] * u[j];
}

}  // namespace

double corner_kappa_mod_add_point_derivatives(const double e1[3], const double e2[3], const double e3[3],
                                              double a1, double a2, double a3, double V0, double c,
                                              double g[3], double H[9]) {
  // The value exactly as corner_kappa_mod<double> computes it (bitwise), so a
  // line search comparing against it sees no summation noise.
  double A, L, V;
  corner_invariants(e1, e2, e3, A, L, V);
  const double delta = adaptive_delta(V, V0, c);
  const double D = regularised_volume(V, delta);
  const double S = std::sqrt(A * L);
  const double kmod = 2.0 * S / D;
  if (!(S > 0) || (a1 == 0 && a2 == 0 && a3 == 0)) return kmod;
  const Vec3 E1{e1[0], e1[1], e1[2]}, E2{e2[0], e2[1], e2[2]}, E3{e3[0], e3[1], e3[2]};
  const Vec3 c12 = cross(E1, E2), c23 = cross(E2, E3), c31 = cross(E3, E1);
  // e_i(t) = e_i + a_i t  =>  e_i x e_j (t) = c_ij + t x w_ij (affine in t).
  const Vec3 w12 = a1 * E2 - a2 * E1, w23 = a2 * E3 - a3 * E2, w31 = a3 * E1 - a1 * E3;
  // A = sum |c_ij + t x w_ij|^2: grad 2 sum w x c, Hessian 2 sum (|w|^2 I - w w^T).
  const Vec3 gA = 2.0 * (cross(w12, c12) + cross(w23, c23) + cross(w31, c31));
  double HA[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (const Vec3* w : {&w12, &w23, &w31}) {
    const double n = norm2(*w);
    HA[0] += 2 * n; HA[4] += 2 * n; HA[8] += 2 * n;
    add_outer(HA, -2.0, *w);
  }
  // L = sum |e_i + a_i t|^2.
  const Vec3 gL = 2.0 * (a1 * E1 + a2 * E2 + a3 * E3);
  const double hL = 2.0 * (a1 * a1 + a2 * a2 + a3 * a3);  // Hessian hL I
  // V = det[e1+a1 t, e2+a2 t, e3+a3 t] is affine in t (a repeated column cancels).
  const Vec3 gV = a1 * c23 + a2 * c31 + a3 * c12;
  // S = sqrt(A L).
  const Vec3 gS = (L * gA + A * gL) / (2.0 * S);
  double HS[9];
  for (int i = 0; i < 9; ++i) HS[i] = L * HA[i] / (2.0 * S);
  for (int i = 0; i < 3; ++i) HS[4 * i] += A * hL / (2.0 * S);
  add_sym(HS, 1.0 / (2.0 * S), gA, gL);
  add_outer(HS, -1.0 / S, gS);
  // 1/D(V): D = V + W, W = sqrt(V^2 + delta^2), delta = V0 s, s = 1/(1 + c e^{V/V0}):
  //   delta' = -s(1-s), delta'' = s(1-s)(1-2s)/V0,
  //   D' = (D + delta delta')/W, D'' = ((delta - V delta')^2 + delta delta'' W^2)/W^3
  // (both written without the cancellation of 1 + (V + delta delta')/W for V << 0).
  const double W = std::sqrt(V * V + delta * delta);
  const double s = delta / V0;
  const double d1 = -s * (1.0 - s), d2 = s * (1.0 - s) * (1.0 - 2.0 * s) / V0;
  const double D1 = (D + delta * d1) / W;
  const double q = delta - V * d1;
  const double D2 = (q * q + delta * d2 * W * W) / (W * W * W);
  const double r0 = 1.0 / D, r1 = -D1 / (D * D), r2 = (2.0 * D1 * D1 - D * D2) / (D * D * D);
  // kappa_mod = 2 S r(V).
  const Vec3 gk = 2.0 * r0 * gS + 2.0 * S * r1 * gV;
  for (int i = 0; i < 3; ++i) g[i] += gk[i];
  for (int i = 0; i < 9; ++i) H[i] += 2.0 * r0 * HS[i];
  add_sym(H, 2.0 * r1, gS, gV);
  add_outer(H, 2.0 * S * r2, gV);
  return kmod;
}

}  // namespace polydual
