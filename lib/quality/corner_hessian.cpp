// Second-order derivatives of one corner's kappa_mod with respect to one mesh
// point (the analytic Newton model of the local scheme, design §7; derivation in
// proofs/quality.md §6).
#include <cmath>

#include "quality/corner.h"

namespace polydual {
namespace {

inline void cross3(const double u[3], const double v[3], double out[3]) {
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}
inline double dot3(const double u[3], const double v[3]) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

// r(V) = 1/D(V) and its first two derivatives in V, where D = V + W,
// W = sqrt(V^2 + delta^2), delta = V0 s, s = 1/(1 + c e^{V/V0}):
//   delta' = -s(1-s), delta'' = s(1-s)(1-2s)/V0,
//   D' = (D + delta delta')/W, D'' = ((delta - V delta')^2 + delta delta'' W^2)/W^3
// (both written without the cancellation of 1 + (V + delta delta')/W for V << 0).
inline void inverse_regularised_volume(double V, double delta, double D, double V0, double& r0, double& r1,
                                       double& r2) {
  const double W = std::sqrt(V * V + delta * delta);
  const double s = delta / V0;
  const double d1 = -s * (1.0 - s), d2 = s * (1.0 - s) * (1.0 - 2.0 * s) / V0;
  const double D1 = (D + delta * d1) / W;
  const double q = delta - V * d1;
  const double D2 = (q * q + delta * d2 * W * W) / (W * W * W);
  r0 = 1.0 / D;
  r1 = -D1 * r0 * r0;
  r2 = (2.0 * D1 * D1 - D * D2) * r0 * r0 * r0;
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
  // Plain arrays (Vec3::operator[] branches on the index) so the loops unroll.
  double c12[3], c23[3], c31[3], w12[3], w23[3], w31[3];
  cross3(e1, e2, c12);
  cross3(e2, e3, c23);
  cross3(e3, e1, c31);
  // e_i(t) = e_i + a_i t  =>  e_i x e_j (t) = c_ij + t x w_ij (affine in t).
  for (int i = 0; i < 3; ++i) {
    w12[i] = a1 * e2[i] - a2 * e1[i];
    w23[i] = a2 * e3[i] - a3 * e2[i];
    w31[i] = a3 * e1[i] - a1 * e3[i];
  }
  // A = sum |c_ij + t x w_ij|^2: grad 2 sum w x c, Hessian 2 sum (|w|^2 I - w w^T).
  double gA[3], t12[3], t23[3], t31[3];
  cross3(w12, c12, t12);
  cross3(w23, c23, t23);
  cross3(w31, c31, t31);
  for (int i = 0; i < 3; ++i) gA[i] = 2.0 * (t12[i] + t23[i] + t31[i]);
  const double nw = dot3(w12, w12) + dot3(w23, w23) + dot3(w31, w31);
  // L = sum |e_i + a_i t|^2: grad 2 sum a_i e_i, Hessian hL I.
  // V = det[e1+a1 t, e2+a2 t, e3+a3 t] is affine in t (a repeated column cancels).
  double gL[3], gV[3], gS[3];
  const double hL = 2.0 * (a1 * a1 + a2 * a2 + a3 * a3);
  const double inv2S = 1.0 / (2.0 * S);
  for (int i = 0; i < 3; ++i) {
    gL[i] = 2.0 * (a1 * e1[i] + a2 * e2[i] + a3 * e3[i]);
    gV[i] = a1 * c23[i] + a2 * c31[i] + a3 * c12[i];
    gS[i] = inv2S * (L * gA[i] + A * gL[i]);  // S = sqrt(A L)
  }
  double r0, r1, r2;
  inverse_regularised_volume(V, delta, D, V0, r0, r1, r2);
  // kappa_mod = 2 S r(V).
  for (int i = 0; i < 3; ++i) g[i] += 2.0 * r0 * gS[i] + 2.0 * S * r1 * gV[i];
  const double k0 = 2.0 * r0, k1 = 2.0 * r1, k2 = 2.0 * S * r2, iS = 1.0 / S;
  const double diag = inv2S * (L * 2.0 * nw + A * hL);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // d2S = (L d2A + A d2L + gA gL^T + gL gA^T) / 2S - gS gS^T / S.
      const double HA_off = -2.0 * (w12[i] * w12[j] + w23[i] * w23[j] + w31[i] * w31[j]);
      const double hs = inv2S * (L * HA_off + gA[i] * gL[j] + gL[i] * gA[j]) - iS * gS[i] * gS[j] +
                        (i == j ? diag : 0.0);
      H[3 * i + j] += k0 * hs + k1 * (gS[i] * gV[j] + gV[i] * gS[j]) + k2 * gV[i] * gV[j];
    }
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
  // Plain arrays (Vec3::operator[] branches on the index) so the loops unroll.
  const double c12[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};  // dV/de3
  const double n12 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2] + e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
  const double d13 = e1[0] * e3[0] + e1[1] * e3[1] + e1[2] * e3[2];
  const double d23 = e2[0] * e3[0] + e2[1] * e3[1] + e2[2] * e3[2];
  // dA/de3 = 2((|e1|^2+|e2|^2) e3 - (e1.e3) e1 - (e2.e3) e2), d2A = 2((..) I - e1e1^T - e2e2^T);
  // dL/de3 = 2 e3, d2L = 2 I.
  double dA[3], dS[3], gk[3];
  const double inv2S = 1.0 / (2.0 * S);
  for (int i = 0; i < 3; ++i) {
    dA[i] = 2.0 * (n12 * e3[i] - d13 * e1[i] - d23 * e2[i]);
    dS[i] = inv2S * (L * dA[i] + A * 2.0 * e3[i]);
  }
  double r0, r1, r2;
  inverse_regularised_volume(V, delta, D, V0, r0, r1, r2);
  for (int i = 0; i < 3; ++i) {
    gk[i] = 2.0 * r0 * dS[i] + 2.0 * S * r1 * c12[i];
    g[i] += a3 * gk[i];
  }
  const double aa = a3 * a3, k0 = 2.0 * r0, k1 = 2.0 * r1, k2 = 2.0 * S * r2, iS = 1.0 / S;
  const double diag = 2.0 * (L * n12 + A) * inv2S;
  const double m2L = -2.0 * L * inv2S;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // d2S_ij = (L d2A + A d2L + dA dL^T + dL dA^T)_ij / 2S - dS_i dS_j / S, dL = 2 e3.
      const double hs = m2L * (e1[i] * e1[j] + e2[i] * e2[j]) + inv2S * 2.0 * (dA[i] * e3[j] + e3[i] * dA[j]) -
                        iS * dS[i] * dS[j] + (i == j ? diag : 0.0);
      H[3 * i + j] += aa * (k0 * hs + k1 * (dS[i] * c12[j] + c12[i] * dS[j]) + k2 * c12[i] * c12[j]);
    }
  return kmod;
}

}  // namespace polydual
