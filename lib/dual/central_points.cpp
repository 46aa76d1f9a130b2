#include "dual/central_points.h"

#include <algorithm>

#include "predicates/predicates.h"

namespace polydual {

namespace {
// A clamped centre stops this relative fraction of the segment short of the
// face it would cross: the rounded point then lies inside by far more than its
// rounding error (2^-20 >> 2^-52), and the exact check passes at once.
constexpr double kClampMargin = 0x1p-20;
// If the exact check fails anyway, t is pulled towards the centroid: first
// kFineSteps times by a growing relative step 1e-12 x 2^iter (keeping the
// point as near the face as possible), then halved; after kMaxSteps in all
// the rounded centroid is taken.
constexpr int kFineSteps = 32, kMaxSteps = 64;
constexpr double kFirstStep = 1e-12;

bool in_closed_tet(const Point3& p, const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  // EXACT: p is in the closed positive tet iff no face sees it on its outer side.
  return orient3d(p, b, c, d) != Sign::Negative && orient3d(a, p, c, d) != Sign::Negative &&
         orient3d(a, b, p, d) != Sign::Negative && orient3d(a, b, c, p) != Sign::Negative;
}
}  // namespace

CentralPoint tet_central_point(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  // c - a = (|u|^2 (v x w) + |v|^2 (w x u) + |w|^2 (u x v)) / (2D), u = b - a, ...
  // (rounded), the exact well-centred signs and the barycentric coordinates
  // in doubles, all from the same products.
  Sign s[4];
  double lam[4], error;
  const Point3 cc = circumcenter_with_signs(a, b, c, d, s, lam, &error);
  // One branch (well-centred or not is a coin toss), not four.
  if ((int(s[0] != Sign::Negative) & int(s[1] != Sign::Negative) & int(s[2] != Sign::Negative) &
       int(s[3] != Sign::Negative)) != 0)
    return {cc, true, error};
  const Vec3 u = b - a, v = c - a, w = d - a;
  // Largest t in [0,1] with centroid + t (cc - centroid) in the tet: for each
  // negative lambda_i, 1/4 + t (lambda_i - 1/4) >= 0.
  double t = 1.0;
  for (int i = 0; i < 4; ++i) {  // selects: which lambdas are negative is a coin toss
    const double ti = 0.25 / (0.25 - std::min(lam[i], 0.0));
    t = std::min(t, ti);
  }
  // Stop short of the face (kClampMargin); the exact check below still decides.
  t *= 1.0 - kClampMargin;
  const Point3 g = a + 0.25 * (u + v + w);
  Point3 p = g + t * (cc - g);
  for (int iter = 0; iter < kMaxSteps; ++iter) {
    if (in_closed_tet(p, a, b, c, d)) return {p, false};
    t *= (iter < kFineSteps ? 1.0 - kFirstStep * double(1ull << iter) : 0.5);
    p = g + t * (cc - g);
  }
  if (in_closed_tet(p, a, b, c, d)) return {p, false};
  return {g, false};  // the rounded centroid of a non-flat tet
}

CentralPoint triangle_central_point(const Point3& a, const Point3& b, const Point3& c) {
  const Vec3 u = b - a, v = c - a;
  // Barycentric weights of the circumcenter: w_A = |BC|^2 (B-A).(C-A), etc.
  const double la = norm2(c - b) * dot(u, v);
  const double lb = norm2(v) * dot(a - b, c - b);
  const double lc = norm2(u) * dot(a - c, b - c);
  const double sum = la + lb + lc;
  Sign s[3];
  triangle_circumcenter_barycentric_signs(a, b, c, s);
  const bool wc = s[0] != Sign::Negative && s[1] != Sign::Negative && s[2] != Sign::Negative;
  double wb = lb / sum, wcc = lc / sum, wa = la / sum;
  if (!wc) {
    double t = 1.0;
    const double l[3] = {wa, wb, wcc};
    for (double li : l)
      if (li < 1.0 / 3) t = std::min(t, (1.0 / 3) / (1.0 / 3 - li));
    wb = 1.0 / 3 + t * (wb - 1.0 / 3);
    wcc = 1.0 / 3 + t * (wcc - 1.0 / 3);
    wb = std::max(wb, 0.0);
    wcc = std::max(wcc, 0.0);
    if (wb + wcc > 1.0) { double k = 1.0 / (wb + wcc); wb *= k; wcc *= k; }
  }
  return {a + wb * u + wcc * v, wc};
}

CentralPoint cap_triangle_point(const Point3& a, const Point3& b, const Point3& c, const bool on_model_edge[3]) {
  Sign s[3];
  triangle_circumcenter_barycentric_signs(a, b, c, s);
  for (int k = 0; k < 3; ++k)
    if (on_model_edge[k] && s[k] != Sign::Positive) return {a + (1.0 / 3) * (b - a) + (1.0 / 3) * (c - a), false};
  return triangle_central_point(a, b, c);
}

CentralPoint triangle_inner_point(const Point3& a, const Point3& b, const Point3& c) {
  Sign s[3];
  triangle_circumcenter_barycentric_signs(a, b, c, s);
  if (s[0] == Sign::Positive && s[1] == Sign::Positive && s[2] == Sign::Positive)
    return triangle_central_point(a, b, c);
  return {a + (1.0 / 3) * (b - a) + (1.0 / 3) * (c - a), false};
}

}  // namespace polydual
