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

double corner_kappa_mod_add_e3_derivatives(const double e1[3], const double e2[3], const double e3[3],
                                           double a3, double V0, double c, double g[3], double H[9]) {
  double A, L, V;
  corner_invariants(e1, e2, e3, A, L, V);
  const double delta = adaptive_delta(V, V0, c);
  const double D = regularised_volume(V, delta);
  const double S = std::sqrt(A * L);
  const double kmod = 2.0 * S / D;
  if (!(S > 0) || a3 == 0) return kmod;
  const Vec3 E1{e1[0], e1[1], e1[2]}, E2{e2[0], e2[1], e2[2]}, E3{e3[0], e3[1], e3[2]};
  const Vec3 c12 = cross(E1, E2);  // dV/de3
  const double n12 = norm2(E1) + norm2(E2), d13 = dot(E1, E3), d23 = dot(E2, E3);
  // dA/de3 = 2((|e1|^2+|e2|^2) e3 - (e1.e3) e1 - (e2.e3) e2), d2A = 2((..) I - e1e1^T - e2e2^T);
  // dL/de3 = 2 e3, d2L = 2 I.
  const Vec3 dA = 2.0 * (n12 * E3 - d13 * E1 - d23 * E2);
  const Vec3 dL = 2.0 * E3;
  const double inv2S = 1.0 / (2.0 * S);
  const Vec3 dS = inv2S * (L * dA + A * dL);
  const double W = std::sqrt(V * V + delta * delta);
  const double s = delta / V0;
  const double d1 = -s * (1.0 - s), d2 = s * (1.0 - s) * (1.0 - 2.0 * s) / V0;
  const double D1 = (D + delta * d1) / W;
  const double q = delta - V * d1;
  const double D2 = (q * q + delta * d2 * W * W) / (W * W * W);
  const double r0 = 1.0 / D, r1 = -D1 / (D * D), r2 = (2.0 * D1 * D1 - D * D2) / (D * D * D);
  const Vec3 gk = (2.0 * r0) * dS + (2.0 * S * r1) * c12;
  for (int i = 0; i < 3; ++i) g[i] += a3 * gk[i];
  const double aa = a3 * a3, k0 = 2.0 * r0, k1 = 2.0 * r1, k2 = 2.0 * S * r2, iS = 1.0 / S;
  const double diag = 2.0 * (L * n12 + A) * inv2S;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      double hs = inv2S * (-2.0 * L * (E1[i] * E1[j] + E2[i] * E2[j]) + dA[i] * dL[j] + dL[i] * dA[j]) -
                  iS * dS[i] * dS[j];
      if (i == j) hs += diag;
      const double h = aa * (k0 * hs + k1 * (dS[i] * c12[j] + c12[i] * dS[j]) + k2 * c12[i] * c12[j]);
      H[3 * i + j] += h;
      if (j != i) H[3 * j + i] += h;
    }
  return kmod;
}

}  // namespace polydual
