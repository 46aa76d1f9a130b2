// Exact predicates. See predicates.h for the contract and proofs/star_filter.md
// for the derivation of the star test's static error bound.
#include "predicates/predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Intersections_3/Segment_3_Triangle_3.h>
#include <CGAL/Intersections_3/Triangle_3_Triangle_3.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <algorithm>
#include <vector>

namespace polydual {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using KP = K::Point_3;
inline KP kp(const Point3& p) { return KP(p.x, p.y, p.z); }

inline Sign to_sign(int s) { return s > 0 ? Sign::Positive : (s < 0 ? Sign::Negative : Sign::Zero); }
inline Sign flip(Sign s) { return static_cast<Sign>(-static_cast<int>(s)); }

template <class NT>
struct V3 {
  NT x, y, z;
};
template <class NT>
V3<NT> sub(const Point3& p, const Point3& q) { return {NT(p.x) - NT(q.x), NT(p.y) - NT(q.y), NT(p.z) - NT(q.z)}; }
template <class NT>
NT dot3(const V3<NT>& a, const V3<NT>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class NT>
V3<NT> cross3(const V3<NT>& a, const V3<NT>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Numerator of the circumcenter's barycentric coordinate at p1 of the tet
// (p0,p1,p2,p3), up to the positive factor 1/(2 D^2), D = det[u,v,w] > 0:
//   c - p0 = (|u|^2 (v x w) + |v|^2 (w x u) + |w|^2 (u x v)) / (2D)
//   lambda_1 = det[c - p0, v, w] / D
//            = (|u|^2 |v x w|^2 + |v|^2 (w x u).(v x w) + |w|^2 (u x v).(v x w)) / (2 D^2).
template <class NT>
NT circ_bary_numerator(const Point3& p0, const Point3& p1, const Point3& p2, const Point3& p3) {
  V3<NT> u = sub<NT>(p1, p0), v = sub<NT>(p2, p0), w = sub<NT>(p3, p0);
  V3<NT> vw = cross3(v, w), wu = cross3(w, u), uv = cross3(u, v);
  return dot3(u, u) * dot3(vw, vw) + dot3(v, v) * dot3(wu, vw) + dot3(w, w) * dot3(uv, vw);
}

template <class F>
Sign filtered_sign(F&& f, std::atomic<std::uint64_t>& exact_counter) {
  {
    CGAL::Protect_FPU_rounding<true> guard;
    CGAL::Interval_nt_advanced r = f(CGAL::Interval_nt_advanced());
    if (r.inf() > 0) return Sign::Positive;
    if (r.sup() < 0) return Sign::Negative;
    if (r.inf() == 0 && r.sup() == 0) return Sign::Zero;
  }
  exact_counter.fetch_add(1, std::memory_order_relaxed);
  return to_sign(static_cast<int>(CGAL::sign(f(CGAL::Mpzf()))));
}
}  // namespace

PredicateCounters& predicate_counters() {
  static PredicateCounters c;
  return c;
}

namespace {
thread_local std::uint64_t t_star_exact = 0;
}  // namespace

std::uint64_t star_exact_this_thread() { return t_star_exact; }

namespace detail {
Sign orient3d_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  // CGAL's orientation(p,q,r,s) is the sign of det[q-p, r-p, s-p] (filtered, exact).
  return to_sign(static_cast<int>(CGAL::orientation(kp(a), kp(b), kp(c), kp(d))));
}
Sign orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) {
  return filtered_sign(
      [&](auto zero) {
        using NT = decltype(zero);
        return (NT(bx) - NT(ax)) * (NT(cy) - NT(ay)) - (NT(by) - NT(ay)) * (NT(cx) - NT(ax));
      },
      predicate_counters().overlap_exact);
}
Sign insphere_exact(const Point3& a, const Point3& b, const Point3& c, const Point3& d, const Point3& e) {
  // side_of_oriented_sphere: ON_POSITIVE_SIDE means inside for positive tets.
  return to_sign(static_cast<int>(CGAL::side_of_oriented_sphere(kp(a), kp(b), kp(c), kp(d), kp(e))));
}
}  // namespace detail

void circumcenter_barycentric_signs(const Point3& a, const Point3& b, const Point3& c,
                                    const Point3& d, Sign out[4]) {
  double lambda[4];
  (void)circumcenter_with_signs(a, b, c, d, out, lambda);
}

namespace {
constexpr double kEps = DBL_EPSILON / 2;  // unit roundoff 2^-53
// Magnitudes of a numerator's tree on absolute values inside which neither
// underflow nor overflow can spoil the filter's bound (proofs/star_filter.md):
// outside, the sign is decided exactly.
constexpr double kFilterMagMin = 1e-200, kFilterMagMax = 1e200;
// The centre's error bound (L9c) is derived for magnitudes in this range
// only; outside it the bound is +infinity (no coincidence is then admitted
// without the exact test).
constexpr double kCentreMagMin = 1e-100, kCentreMagMax = 1e100;
// Absolute terms of e_D and e_n covering underflow residues.
constexpr double kDetUnderflow = 1e-250, kNumUnderflow = 1e-240;

// The semi-static filter of the four barycentric numerators of a tet's
// circumcentre (proofs/star_filter.md, §circumcenter), and what the centre's
// error bound needs, all from the same products.
struct CircumFilter {
  double val[4], bound[4];  // the numerators in doubles and their error bounds
  int range[4];             // 1 where the magnitudes rule out under/overflow
  double D, PD, N_star;  // det[u, v, w], its permanent, N* (L9c)
  Point3 center;
};

// For b, c, d the orders start at a and rotate (u, v, w) = (b-a, c-a, d-a),
// so the three share their cross products: with n = |u|^2 (v x w) + |v|^2
// (w x u) + |w|^2 (u x v), the numerators are n.(v x w), n.(w x u), n.(u x v)
// (each summed in the order of circ_bary_numerator, so the bound is the
// same; the rounding error of the degree-6 polynomial is below 64 eps mag).
// The numerator at a is not computed from its own order (b, a, d, c): the
// four numerators sum to 2 D^2 (the barycentrics sum to 1), so
// N_a = 2 D^2 - N_b - N_c - N_d, with the error bound of L9b (ibid.):
//   |fl(N_a) - N_a| <= 128 eps (|fl(N_a)| + P_D^2 + mag_b + mag_c + mag_d),
// P_D the permanent of D. Inlined: it runs once per tet, in the dual's
// hottest loop, and its temporaries stay in registers.
[[gnu::always_inline]] inline CircumFilter circum_filter(const Point3& a, const Point3& b, const Point3& c,
                                                         const Point3& d, double lambda[4]) {
  auto acr = [](const Vec3& x, const Vec3& y) {
    return Vec3{x.y * y.z + x.z * y.y, x.z * y.x + x.x * y.z, x.x * y.y + x.y * y.x};
  };
  auto fabs3 = [](const Vec3& x) { return Vec3{std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)}; };
  auto in_range = [](double m) { return int(m > kFilterMagMin) & int(m < kFilterMagMax); };
  CircumFilter f;
  const Vec3 u = b - a, v = c - a, w = d - a;
  const Vec3 au = fabs3(u), av = fabs3(v), aw = fabs3(w);
  const Vec3 vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
  const Vec3 avw = acr(av, aw), awu = acr(aw, au), auv = acr(au, av);
  const double nu = dot(u, u), nv = dot(v, v), nw = dot(w, w);
  double mag[4];
  f.val[1] = nu * dot(vw, vw) + nv * dot(wu, vw) + nw * dot(uv, vw);
  mag[1] = nu * dot(avw, avw) + nv * dot(awu, avw) + nw * dot(auv, avw);
  f.val[2] = nv * dot(wu, wu) + nw * dot(uv, wu) + nu * dot(vw, wu);
  mag[2] = nv * dot(awu, awu) + nw * dot(auv, awu) + nu * dot(avw, awu);
  f.val[3] = nw * dot(uv, uv) + nu * dot(vw, uv) + nv * dot(wu, uv);
  mag[3] = nw * dot(auv, auv) + nu * dot(avw, auv) + nv * dot(awu, auv);
  const double D = dot(u, vw), PD = dot(au, avw);
  f.val[0] = 2.0 * D * D - (f.val[1] + f.val[2] + f.val[3]);
  mag[0] = PD * PD;
  for (int i = 1; i < 4; ++i) f.bound[i] = 64.0 * kEps * mag[i];
  f.bound[0] = 128.0 * kEps * (std::fabs(f.val[0]) + mag[0] + mag[1] + mag[2] + mag[3]);
  for (int i = 0; i < 4; ++i) f.range[i] = in_range(mag[i]);
  // Doubles only (not decisions): c - a = n / (2D), lambda_i = val_i / (2 D^2).
  const Vec3 n = nu * vw + nv * wu + nw * uv;
  const Vec3 q = n / (2.0 * D);
  f.center = a + q;
  f.D = D;
  f.PD = PD;
  // N* >= every coordinate of n's tree on absolute values.
  f.N_star = (nu + nv + nw) * ((avw.x + avw.y + avw.z) + (awu.x + awu.y + awu.z) + (auv.x + auv.y + auv.z));
  const double inv = 1.0 / (2.0 * D * D);
  for (int i = 1; i < 4; ++i) lambda[i] = f.val[i] * inv;
  lambda[0] = 1.0 - lambda[1] - lambda[2] - lambda[3];
  return f;
}

// L9c: with e_D = 9 eps P_D, e_n = 13 eps N* (N* bounding every coordinate
// of n's tree on absolute values, so |n~_k| <= N* too) and Dl = |D~| - e_D > 0,
//   |c~_k - c_k| <= (e_n + (N* + e_n) e_D / Dl) / (2 |D~|) + 1.01 eps (|q~_k| + |c~_k|),
// |q~_k| <= 1.01 N* / (2 |D~|); doubled for the rounding of the bound itself.
// Magnitudes are kept in (kCentreMagMin, kCentreMagMax), and Dl above half
// of |D~| (near-flat tets get no bound). Out of line, on scalars: inlined
// into the filter it cost ~20 more instructions per tet (callgrind), the
// filter's temporaries then being spilled around it.
[[gnu::noinline]] double centre_error(double D, double PD, double N_star, Point3 center) {
  const double eD = 9.0 * kEps * PD + kDetUnderflow, aD = std::fabs(D), Dl = aD - eD;
  if (!(PD > kCentreMagMin && PD < kCentreMagMax && N_star < kCentreMagMax && Dl > 0.5 * aD))
    return std::numeric_limits<double>::infinity();
  const double inv = 1.0 / (2.0 * aD), en = 13.0 * kEps * N_star + kNumUnderflow;
  const double cmax = std::max(std::max(std::fabs(center.x), std::fabs(center.y)), std::fabs(center.z));
  return 2.0 * ((en + (N_star + en) * (eD / Dl)) * inv + 1.01 * kEps * (1.01 * N_star * inv + cmax));
}
double centre_error(const CircumFilter& f) { return centre_error(f.D, f.PD, f.N_star, f.center); }

[[gnu::always_inline]] inline bool decided(const CircumFilter& f, int i) {
  return ((int(f.val[i] > f.bound[i]) | int(f.val[i] < -f.bound[i])) & f.range[i]) != 0;
}
}  // namespace

Point3 circumcenter_with_signs(const Point3& a, const Point3& b, const Point3& c, const Point3& d, Sign out[4],
                               double lambda[4], double* error) {
  const CircumFilter f = circum_filter(a, b, c, d, lambda);
  // Each sign is a coin toss (is the circumcentre beyond this face?): taken as
  // the difference of two comparisons, with one branch for "all four decided".
  int all_decided = 1;
  for (int i = 0; i < 4; ++i) {
    const int pos = f.val[i] > f.bound[i], neg = f.val[i] < -f.bound[i];
    all_decided &= (pos | neg) & f.range[i];
    out[i] = static_cast<Sign>(pos - neg);
  }
  if (all_decided) [[likely]] {
    // The centre's bound is computed only for a well-centred tet (the only
    // ones whose centres are compared).
    if (error)
      *error = (int(out[0] != Sign::Negative) & int(out[1] != Sign::Negative) & int(out[2] != Sign::Negative) &
                int(out[3] != Sign::Negative))
                   ? centre_error(f)
                   : std::numeric_limits<double>::infinity();
    return f.center;
  }
  // Orientation-preserving orders that bring each vertex to slot 1 of
  // circ_bary_numerator: a -> (b,a,d,c), b -> (a,b,c,d), c -> (a,c,d,b), d -> (a,d,b,c).
  const Point3* p[4] = {&a, &b, &c, &d};
  static constexpr int perm[4][4] = {{1, 0, 3, 2}, {0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}};
  for (int i = 0; i < 4; ++i) {
    if (decided(f, i)) continue;
    const auto& q = perm[i];
    out[i] = filtered_sign(
        [&](auto zero) {
          using NT = decltype(zero);
          return circ_bary_numerator<NT>(*p[q[0]], *p[q[1]], *p[q[2]], *p[q[3]]);
        },
        predicate_counters().circ_exact);
  }
  if (error) *error = centre_error(f);
  return f.center;
}

void triangle_circumcenter_barycentric_signs(const Point3& a, const Point3& b, const Point3& c,
                                             Sign out[3]) {
  // lambda_A is proportional to |BC|^2 (|AB|^2 + |AC|^2 - |BC|^2) = 2|BC|^2 (B-A).(C-A).
  auto& cnt = predicate_counters();
  const Point3* p[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const Point3 &o = *p[i], &q = *p[(i + 1) % 3], &r = *p[(i + 2) % 3];
    out[i] = filtered_sign(
        [&](auto zero) {
          using NT = decltype(zero);
          return dot3(sub<NT>(q, o), sub<NT>(r, o));
        },
        cnt.circ_exact);
  }
}

namespace {
template <class NT>
NT star_det(const Point3& a, const Point3& b, std::span<const Point3> face, std::span<const Point3> cell) {
  V3<NT> u = sub<NT>(b, a);
  V3<NT> s{NT(0), NT(0), NT(0)}, t{NT(0), NT(0), NT(0)};
  for (const Point3& p : face) {
    V3<NT> d = sub<NT>(p, a);
    s.x = s.x + d.x; s.y = s.y + d.y; s.z = s.z + d.z;
  }
  for (const Point3& q : cell) {
    V3<NT> d = sub<NT>(q, a);
    t.x = t.x + d.x; t.y = t.y + d.y; t.z = t.z + d.z;
  }
  return dot3(u, cross3(s, t));
}
}  // namespace

Sign decomposition_tet_sign(const Point3& a, const Point3& b, std::span<const Point3> face,
                            std::span<const Point3> cell) {
  auto& cnt = predicate_counters();
  // Static filter (proofs/star_filter.md): with k = |face|, m = |cell|,
  //   |fl(det) - det| <= (k + m + 10) * eps * P,
  //   P = |u|.( |S|abs x |T|abs )  (permanent on absolute values),
  // where |S|abs = sum |fl(p - a)| and likewise |T|abs, all computed in doubles.
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  double sx = 0, sy = 0, sz = 0, tx = 0, ty = 0, tz = 0;
  double asx = 0, asy = 0, asz = 0, atx = 0, aty = 0, atz = 0;
  for (const Point3& p : face) {
    const double dx = p.x - a.x, dy = p.y - a.y, dz = p.z - a.z;
    sx += dx; sy += dy; sz += dz;
    asx += std::fabs(dx); asy += std::fabs(dy); asz += std::fabs(dz);
  }
  for (const Point3& q : cell) {
    const double dx = q.x - a.x, dy = q.y - a.y, dz = q.z - a.z;
    tx += dx; ty += dy; tz += dz;
    atx += std::fabs(dx); aty += std::fabs(dy); atz += std::fabs(dz);
  }
  const double det = ux * (sy * tz - sz * ty) + uy * (sz * tx - sx * tz) + uz * (sx * ty - sy * tx);
  const double perm = std::fabs(ux) * (asy * atz + asz * aty) + std::fabs(uy) * (asz * atx + asx * atz) +
                      std::fabs(uz) * (asx * aty + asy * atx);
  const double eps = DBL_EPSILON / 2;  // unit roundoff 2^-53
  const double bound = (double(face.size() + cell.size()) + 10.0) * eps * perm * (1.0 + 1e-6);
  // Below ~1e-250 the bound could be spoiled by underflow: go exact.
  if (std::isfinite(perm) && perm > 1e-250) {
    if (det > bound) return Sign::Negative;   // det > 0  ->  vol(R,a,b,F) < 0
    if (det < -bound) return Sign::Positive;
  }
  cnt.star_exact.fetch_add(1, std::memory_order_relaxed);
  ++t_star_exact;
  return flip(to_sign(static_cast<int>(CGAL::sign(star_det<CGAL::Mpzf>(a, b, face, cell)))));
}

PointSums point_sums(std::span<const Point3> pts, const Point3& origin) {
  PointSums r;
  r.origin = origin;
  r.n = pts.size();
  for (const Point3& p : pts) {
    const double dx = p.x - origin.x, dy = p.y - origin.y, dz = p.z - origin.z;
    r.sx += dx; r.sy += dy; r.sz += dz;
    r.ax += std::fabs(dx); r.ay += std::fabs(dy); r.az += std::fabs(dz);
  }
  return r;
}

Sign decomposition_tet_sign_inexact(const Point3& a, const Point3& b, std::span<const Point3> face,
                                    std::span<const Point3> cell) {
  const double d = star_det<double>(a, b, face, cell);
  return d > 0 ? Sign::Negative : (d < 0 ? Sign::Positive : Sign::Zero);
}

Sign orient3d_centroid(const Point3& a, const Point3& b, const Point3& c, const Point3& p, const Point3& q,
                       const Point3& r) {
  return filtered_sign(
      [&](auto zero) {
        using NT = decltype(zero);
        const V3<NT> u = sub<NT>(b, a), v = sub<NT>(c, a);
        const V3<NT> gp = sub<NT>(p, a), gq = sub<NT>(q, a), gr = sub<NT>(r, a);
        const V3<NT> g{gp.x + gq.x + gr.x, gp.y + gq.y + gr.y, gp.z + gq.z + gr.z};
        return dot3(cross3(u, v), g);
      },
      predicate_counters().overlap_exact);
}

Sign surface_turn(const Point3& r, const Point3& p, const Point3& q, const Vec3& n) {
  return filtered_sign(
      [&](auto zero) {
        using NT = decltype(zero);
        const V3<NT> u = sub<NT>(p, r), v = sub<NT>(q, r);
        return dot3(cross3(u, v), V3<NT>{NT(n.x), NT(n.y), NT(n.z)});
      },
      predicate_counters().surface_exact);
}

Sign coplanar_orientation(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return to_sign(static_cast<int>(CGAL::coplanar_orientation(kp(a), kp(b), kp(c), kp(d))));
}

bool segment_meets_triangle(const Point3& p, const Point3& q, const Point3& a, const Point3& b, const Point3& c) {
  return CGAL::do_intersect(K::Segment_3(kp(p), kp(q)), K::Triangle_3(kp(a), kp(b), kp(c)));
}

bool triangles_meet(const Point3& a, const Point3& b, const Point3& c, const Point3& p, const Point3& q,
                    const Point3& r) {
  return CGAL::do_intersect(K::Triangle_3(kp(a), kp(b), kp(c)), K::Triangle_3(kp(p), kp(q), kp(r)));
}

}  // namespace polydual
