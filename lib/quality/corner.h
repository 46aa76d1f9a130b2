// Condition number of a trivalent corner (paper 3.2, eq. 1-3; design §6), written
// as templates so that one text serves doubles, finite differences and
// ceres::Jet (exact derivatives).
//
// A corner at point p has edge vectors e1, e2, e3 (right-handed when valid):
//   L = |e1|^2 + |e2|^2 + |e3|^2
//   A = |e1 x e2|^2 + |e2 x e3|^2 + |e3 x e1|^2
//   V = (e1 x e2) . e3
//   kappa     = sqrt(A L) / V                         (>= 3; 3 = right unit corner)
//   kappa_mod = 2 sqrt(A L) / (V + sqrt(V^2 + delta^2))   (Escobar et al.)
//   delta(V)  = V0 / (1 + c exp(V / V0))              (paper eq. 3, scaled by V0)
// The extracted paper text prints A with "e3 x e2", L with "e1" three times and
// kappa_mod without the square root; proofs/quality.md records the repairs and
// the limit checks that pin them (tests/quality/quality_test.cpp).
#pragma once
#include <ceres/jet.h>

#include <cmath>

#include "core/vec3.h"

namespace polydual {

// Default c of eq. 3 (the paper: "between 10 and 100"). With c = 50,
// delta(0) = V0/51 (a steep but finite barrier at V = 0) and
// delta(V0) = V0/(1+50e) ~ 0.0073 V0, so kappa_mod/kappa - 1 ~ 1e-5 for a
// healthy corner: the objective is the condition number wherever it matters.
inline constexpr double kDefaultDeltaC = 50.0;

// The three corner invariants A, L, V.
template <class T>
inline void corner_invariants(const T e1[3], const T e2[3], const T e3[3], T& A, T& L, T& V) {
  const T c12[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0]};
  const T c23[3] = {e2[1] * e3[2] - e2[2] * e3[1], e2[2] * e3[0] - e2[0] * e3[2],
                    e2[0] * e3[1] - e2[1] * e3[0]};
  const T c31[3] = {e3[1] * e1[2] - e3[2] * e1[1], e3[2] * e1[0] - e3[0] * e1[2],
                    e3[0] * e1[1] - e3[1] * e1[0]};
  A = c12[0] * c12[0] + c12[1] * c12[1] + c12[2] * c12[2] + c23[0] * c23[0] + c23[1] * c23[1] +
      c23[2] * c23[2] + c31[0] * c31[0] + c31[1] * c31[1] + c31[2] * c31[2];
  L = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2] + e2[0] * e2[0] + e2[1] * e2[1] +
      e2[2] * e2[2] + e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2];
  V = c12[0] * e3[0] + c12[1] * e3[1] + c12[2] * e3[2];
}

// Adaptive delta (eq. 3). The paper's 1/(1 + c e^{V/V0}) is dimensionless while
// V is a length^3: we scale it by V0 so delta has V's units and kappa_mod stays
// invariant under scaling. Written without overflow: for V > 0 we use
// e^{-x}/(e^{-x} + c), which tends to 0 smoothly instead of computing inf/inf.
template <class T>
inline T adaptive_delta(const T& V, double V0, double c) {
  using std::exp;
  const T x = V / V0;
  if (x > 0.0) {
    const T e = exp(-x);
    return V0 * e / (e + c);
  }
  return V0 / (1.0 + c * exp(x));
}

// V + sqrt(V^2 + delta^2) without cancellation for V << 0
// (= delta^2 / (sqrt(V^2+delta^2) - V) there). Positive whenever delta != 0.
template <class T>
inline T regularised_volume(const T& V, const T& delta) {
  using std::sqrt;
  const T W = sqrt(V * V + delta * delta);
  if (V >= 0.0) return V + W;
  return delta * delta / (W - V);
}

template <class T>
inline T corner_kappa(const T e1[3], const T e2[3], const T e3[3]) {
  using std::sqrt;
  T A, L, V;
  corner_invariants(e1, e2, e3, A, L, V);
  return sqrt(A * L) / V;
}

// kappa_mod with a given delta (delta -> 0 recovers kappa for V > 0).
template <class T>
inline T corner_kappa_mod_delta(const T e1[3], const T e2[3], const T e3[3], const T& delta) {
  using std::sqrt;
  T A, L, V;
  corner_invariants(e1, e2, e3, A, L, V);
  return 2.0 * sqrt(A * L) / regularised_volume(V, delta);
}

// kappa_mod with the adaptive delta(V) of eq. 3 (what the optimisers minimise).
template <class T>
inline T corner_kappa_mod(const T e1[3], const T e2[3], const T e3[3], double V0, double c) {
  using std::sqrt;
  T A, L, V;
  corner_invariants(e1, e2, e3, A, L, V);
  return 2.0 * sqrt(A * L) / regularised_volume(V, adaptive_delta(V, V0, c));
}

// kappa and kappa_mod of one corner from one evaluation of its invariants
// (the same bits as corner_kappa and corner_kappa_mod: the same expressions).
inline double corner_kappa_and_mod(const double e1[3], const double e2[3], const double e3[3], double V0, double c,
                                   double* kappa) {
  double A, L, V;
  corner_invariants(e1, e2, e3, A, L, V);
  const double S = std::sqrt(A * L);
  *kappa = S / V;
  return 2.0 * S / regularised_volume(V, adaptive_delta(V, V0, c));
}

// kappa_mod and its gradient with respect to e1, e2, e3 (hand-derived adjoint,
// used by the global gradient; checked against Jets in tests/optim/optim_test.cpp):
//   d kappa_mod = (L dA + A dL) / (D S) - (kappa_mod / D) D'(V) dV,
//   S = sqrt(A L), D = V + W, W = sqrt(V^2 + delta^2),
//   D'(V) = 1 + (V + delta delta'(V)) / W, delta' = -s (1 - s), s = delta / V0.
double corner_kappa_mod_gradient(const Vec3& e1, const Vec3& e2, const Vec3& e3, double V0,
                                 double c, Vec3& g1, Vec3& g2, Vec3& g3);

// kappa_mod of the corner (e1, e2, e3) moved by one point x: e_i(t) = e_i + a_i t,
// where a_i = d e_i / d x is a scalar (points enter corners directly, with
// weight +-1, or through the means F and R, with weight 1/|face| or 1/|cell|).
// Adds the gradient d kappa_mod/dt (3) and Hessian (3x3, row-major) at t = 0 to
// g and H; returns kappa_mod, bitwise equal to corner_kappa_mod<double>.
// Closed form (proofs/quality.md §6): e_i x e_j and V are affine in t, so
// A, L are quadratics with explicit Hessians and V has none.
double corner_kappa_mod_add_point_derivatives(const double e1[3], const double e2[3], const double e3[3],
                                              double a1, double a2, double a3, double V0, double c,
                                              double g[3], double H[9]);
// The same when only e3 moves (a1 = a2 = 0): the corners that see the point only
// through the region centre R, most of a point's corners; cheaper.
double corner_kappa_mod_add_e3_derivatives(const double e1[3], const double e2[3], const double e3[3],
                                           double a3, double V0, double c, double g[3], double H[9]);

}  // namespace polydual
