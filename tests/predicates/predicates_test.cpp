// lib/predicates: sign conventions and exactness against rational arithmetic.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpq.h>

#include <cmath>
#include <random>
#include <vector>

#include "predicates/predicates.h"

using namespace polydual;

namespace {
// Rational reference for the circumcentre tests.
using Q = CGAL::Gmpq;
using QP = std::array<Q, 3>;
QP qsub(const QP& x, const QP& y) { return QP{x[0] - y[0], x[1] - y[1], x[2] - y[2]}; }
Q qdot(const QP& x, const QP& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }
Q qdet3(const QP& x, const QP& y, const QP& z) {
  return x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) + x[2] * (y[0] * z[1] - y[1] * z[0]);
}
// The exact tet: v[0..3] as rationals, made positive (swapping v[2], v[3]),
// and its exact circumcentre. valid == false for a flat tet.
struct RationalTet {
  QP q[4], cc;
  bool valid = false;
  explicit RationalTet(Point3 v[4]) {
    for (int i = 0; i < 4; ++i) q[i] = {Q(v[i].x), Q(v[i].y), Q(v[i].z)};
    Q D = qdet3(qsub(q[1], q[0]), qsub(q[2], q[0]), qsub(q[3], q[0]));
    if (D == 0) return;
    if (D < 0) { std::swap(v[2], v[3]); std::swap(q[2], q[3]); D = -D; }
    // Circumcentre c - q0 = x with 2 e_k . x = |e_k|^2 (Cramer).
    const QP e1 = qsub(q[1], q[0]), e2 = qsub(q[2], q[0]), e3 = qsub(q[3], q[0]);
    const QP r{qdot(e1, e1) / 2, qdot(e2, e2) / 2, qdot(e3, e3) / 2};
    const QP c0{e1[0], e2[0], e3[0]}, c1{e1[1], e2[1], e3[1]}, c2{e1[2], e2[2], e3[2]};
    cc = {q[0][0] + qdet3(r, c1, c2) / D, q[0][1] + qdet3(c0, r, c2) / D, q[0][2] + qdet3(c0, c1, r) / D};
    valid = true;
  }
  // Sign of the circumcentre's barycentric coordinate at vertex i: the volume
  // with vertex i replaced by the circumcentre.
  int bary_sign(int i) const {
    QP t[4] = {q[0], q[1], q[2], q[3]};
    t[i] = cc;
    return CGAL::sign(qdet3(qsub(t[1], t[0]), qsub(t[2], t[0]), qsub(t[3], t[0])));
  }
};
}  // namespace

TEST(Predicates, OrientConventionOnUnitTet) {
  const Point3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  EXPECT_EQ(orient3d(o, x, y, z), Sign::Positive);
  EXPECT_EQ(orient3d(o, y, x, z), Sign::Negative);
  EXPECT_EQ(orient3d(o, x, y, Point3{0.25, 0.25, 0}), Sign::Zero);
}

TEST(Predicates, InsphereCospherical) {
  // The 8 corners of a cube are cospherical.
  const Point3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
  EXPECT_EQ(insphere(a, b, c, d, Point3{1, 1, 1}), Sign::Zero);
  EXPECT_EQ(insphere(a, b, c, d, Point3{0.5, 0.5, 0.5}), Sign::Positive);
  EXPECT_EQ(insphere(a, b, c, d, Point3{2, 2, 2}), Sign::Negative);
}

TEST(Predicates, CircumcenterOfCornerTetIsOutside) {
  // Right corner tet: circumcenter (1/2,1/2,1/2), barycentric (-1/2, 1/2, 1/2, 1/2).
  Sign s[4];
  circumcenter_barycentric_signs({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, s);
  EXPECT_EQ(s[0], Sign::Negative);
  EXPECT_EQ(s[1], Sign::Positive);
  EXPECT_EQ(s[2], Sign::Positive);
  EXPECT_EQ(s[3], Sign::Positive);
  // Kuhn tet (0,0,0),(1,0,0),(1,1,0),(1,1,1): circumcenter = midpoint of the
  // diagonal (an edge): exactly two barycentric coordinates are zero.
  circumcenter_barycentric_signs({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}, s);
  int zeros = 0, neg = 0;
  for (Sign x : s) { zeros += x == Sign::Zero; neg += x == Sign::Negative; }
  EXPECT_EQ(zeros, 2);
  EXPECT_EQ(neg, 0);
  Sign t[3];
  triangle_circumcenter_barycentric_signs({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, t);  // right angle at 0
  EXPECT_EQ(t[0], Sign::Zero);
  EXPECT_EQ(t[1], Sign::Positive);
  EXPECT_EQ(t[2], Sign::Positive);
}

// The filtered orient3d and insphere agree with CGAL's exact predicates on
// random, nearly degenerate and exactly degenerate inputs (the filters must
// never decide a wrong sign; undecided cases go to CGAL).
TEST(Predicates, FilteredOrientAndInsphereMatchCgal) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  auto kp = [](const Point3& p) { return K::Point_3(p.x, p.y, p.z); };
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> U(-1, 1);
  int zero_o = 0, zero_s = 0, pos_s = 0, neg_s = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    Point3 p[5];
    for (auto& x : p) x = {U(rng), U(rng), U(rng)};
    if (iter % 4 == 1) p[3] = p[0] + 0.3 * (p[1] - p[0]) + 0.7 * (p[2] - p[0]);  // nearly coplanar (rounded)
    if (iter % 4 == 2)  // on a lattice: exact coplanarities and cosphericities
      for (auto& x : p) x = {std::round(2 * x.x), std::round(2 * x.y), std::round(2 * x.z)};
    if (iter % 4 == 3) {  // e on the circumsphere of a right corner, up to rounding
      const double s = 1 + U(rng);
      p[0] = {0, 0, 0}; p[1] = {s, 0, 0}; p[2] = {0, s, 0}; p[3] = {0, 0, s};
      p[4] = {s, s, (iter % 8 == 3) ? s : s * (1 + 1e-16)};
    }
    const int o = static_cast<int>(CGAL::orientation(kp(p[0]), kp(p[1]), kp(p[2]), kp(p[3])));
    ASSERT_EQ(static_cast<int>(orient3d(p[0], p[1], p[2], p[3])), o) << iter;
    zero_o += o == 0;
    const int sp = static_cast<int>(CGAL::side_of_oriented_sphere(kp(p[0]), kp(p[1]), kp(p[2]), kp(p[3]), kp(p[4])));
    ASSERT_EQ(static_cast<int>(insphere(p[0], p[1], p[2], p[3], p[4])), sp) << iter;
    zero_s += sp == 0;
    pos_s += sp > 0;
    neg_s += sp < 0;
  }
  EXPECT_GT(zero_o, 100);
  EXPECT_GT(zero_s, 100);
  EXPECT_GT(pos_s, 1000);
  EXPECT_GT(neg_s, 1000);
}

// Each out[i] is the sign of the circumcentre's barycentric coordinate at
// vertex i: checked against Gmpq (solve for the circumcentre, then the
// volumes with vertex i replaced by it) on random and near-degenerate tets.
TEST(Predicates, CircumcenterSignsMatchRationalBarycentrics) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> U(-1, 1);
  int checked = 0, negatives = 0, zeros = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    Point3 v[4];
    for (auto& x : v) x = {U(rng), U(rng), U(rng)};
    if (iter % 3 == 0) v[3] = {v[0].x, v[1].y, v[2].z};  // mixed coordinates
    if (iter % 5 == 0) for (auto& x : v) x = {std::round(4 * x.x) / 4, std::round(4 * x.y) / 4, std::round(4 * x.z) / 4};
    const RationalTet rt(v);
    if (!rt.valid) continue;
    Sign s[4];
    circumcenter_barycentric_signs(v[0], v[1], v[2], v[3], s);
    for (int i = 0; i < 4; ++i) {
      const int expect = rt.bary_sign(i);
      ASSERT_EQ(static_cast<int>(s[i]), expect) << "iteration " << iter << ", vertex " << i;
      negatives += expect < 0;
      zeros += expect == 0;
    }
    ++checked;
  }
  EXPECT_GT(checked, 2500);
  EXPECT_GT(negatives, 1000);  // badly centred tets are common among random ones
  EXPECT_GT(zeros, 0);         // and the lattice ones hit exact zeros
}

// The sign at vertex a comes from the identity N_a = 2 D^2 - N_b - N_c - N_d
// (proofs/star_filter.md, L9b), where cancellation is worst: circumcentres on
// or within a few ulps of face bcd. Apex a on the sphere over the unit circle
// through b, c, d has lambda_a = 0 exactly; nudging any coordinate by ulps
// makes it tiny and of either sign. Checked against rational arithmetic.
TEST(Predicates, CircumcenterSignAtApexNearOppositeFace) {
  auto nudge = [](double x, int ulps) {
    for (; ulps > 0; --ulps) x = std::nextafter(x, 2.0);
    for (; ulps < 0; ++ulps) x = std::nextafter(x, -2.0);
    return x;
  };
  int zeros = 0, positives = 0, negatives = 0;
  auto check = [&](Point3 v[4], const std::string& what) {
    const RationalTet rt(v);
    if (!rt.valid) return;
    Sign s[4];
    circumcenter_barycentric_signs(v[0], v[1], v[2], v[3], s);
    const int expect = rt.bary_sign(0);
    EXPECT_EQ(static_cast<int>(s[0]), expect) << what;
    zeros += expect == 0;
    positives += expect > 0;
    negatives += expect < 0;
  };
  for (int k = -3; k <= 3; ++k)
    for (int which = 0; which < 12; ++which) {
      // b, c, d on the unit circle z = 0 (dyadic points), a = north pole.
      Point3 v[4] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
      double* coord[12] = {&v[0].x, &v[0].y, &v[0].z, &v[1].x, &v[1].y, &v[1].z,
                           &v[2].x, &v[2].y, &v[2].z, &v[3].x, &v[3].y, &v[3].z};
      *coord[which] = nudge(*coord[which], k);
      check(v, "nudge " + std::to_string(k) + " ulps on coordinate " + std::to_string(which));
    }
  // Random triangles far from the origin, the apex rounded onto the sphere
  // over their circumcircle: lambda_a is tiny and its sign is at the mercy of
  // rounding (plain doubles get it wrong here).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  const int before = zeros + positives + negatives;
  for (int iter = 0; iter < 2000; ++iter) {
    const Vec3 off{1000.0 + U(rng), -700.0 + U(rng), 300.0 + U(rng)};
    Point3 b{U(rng), U(rng), U(rng)}, c{U(rng), U(rng), U(rng)}, d{U(rng), U(rng), U(rng)};
    const Vec3 n = cross(c - b, d - b);
    if (norm(n) < 0.1) continue;
    // Circumcentre of bcd in its plane, then the apex over it at the circumradius.
    const Vec3 e1 = c - b, e2 = d - b;
    const double a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2), det = a11 * a22 - a12 * a12;
    const double s1 = (a22 * a11 - a12 * a22) / (2 * det), s2 = (a11 * a22 - a12 * a11) / (2 * det);
    const Point3 o = b + s1 * e1 + s2 * e2;
    const double rad = norm(b - o);
    Point3 v[4] = {o + (rad / norm(n)) * n + off, b + off, c + off, d + off};
    check(v, "random apex " + std::to_string(iter));
  }
  EXPECT_GT(zeros, 0);
  EXPECT_GT(positives, 10);
  EXPECT_GT(negatives, 10);
  EXPECT_GT(zeros + positives + negatives - before, 1500);
}

// L9c: the error bound returned with the rounded circumcentre of a
// well-centred tet holds against the exact (rational) circumcentre, for
// ordinary and far-off tets; near-flat, tiny and huge ones get +infinity.
TEST(Predicates, CircumcentreErrorBoundHolds) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> U(-1, 1);
  int bounded = 0, unbounded = 0;
  double worst = 0;  // largest error / bound seen
  for (int iter = 0; iter < 4000; ++iter) {
    const int kind = iter % 5;
    const double scale = kind == 3 ? 1e-50 : (kind == 4 ? 1e40 : 1.0);
    const Vec3 off = kind == 2 ? Vec3{1e6 * U(rng), 1e6 * U(rng), 1e6 * U(rng)} : Vec3{0, 0, 0};
    // Perturbed regular tets (mostly well-centred: the bound is given for
    // those only), and near-flat ones (never well-centred: +infinity).
    const Point3 reg[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    Point3 v[4];
    for (int i = 0; i < 4; ++i) v[i] = scale * (reg[i] + 0.35 * Vec3{U(rng), U(rng), U(rng)}) + off;
    if (kind == 1) v[3] = 0.5 * (v[0] + v[1]) + 1e-9 * scale * Vec3{U(rng), U(rng), U(rng)};  // near-flat
    const RationalTet rt(v);
    if (!rt.valid) continue;
    Sign s[4];
    double lam[4], err = -1;
    const Point3 c = circumcenter_with_signs(v[0], v[1], v[2], v[3], s, lam, &err);
    ASSERT_GE(err, 0.0);
    if (std::isinf(err)) { ++unbounded; continue; }
    ++bounded;
    const double got[3] = {c.x, c.y, c.z};
    for (int k = 0; k < 3; ++k) {
      Q diff = Q(got[k]) - rt.cc[k];
      if (diff < 0) diff = -diff;
      ASSERT_LE(diff, Q(err)) << "iteration " << iter << " (kind " << kind << "), coordinate " << k;
      if (err > 0) worst = std::max(worst, CGAL::to_double(diff) / err);
    }
  }
  EXPECT_GT(bounded, 1200);    // well-centred ordinary and far-off tets
  EXPECT_GT(unbounded, 1600);  // near-flat tets, tiny and huge magnitudes: the exact test decides
  EXPECT_GT(worst, 1e-3) << "the bound is not vacuously loose";
}

namespace {
int rational_star_sign(const Point3& a, const Point3& b, const std::vector<Point3>& face,
                       const std::vector<Point3>& cell) {
  using Q = CGAL::Gmpq;
  auto sub = [](const Point3& p, const Point3& q) { return std::array<Q, 3>{Q(p.x) - Q(q.x), Q(p.y) - Q(q.y), Q(p.z) - Q(q.z)}; };
  auto u = sub(b, a);
  std::array<Q, 3> S{Q(0), Q(0), Q(0)}, T{Q(0), Q(0), Q(0)};
  for (auto& p : face) { auto d = sub(p, a); for (int i = 0; i < 3; ++i) S[i] += d[i]; }
  for (auto& q : cell) { auto d = sub(q, a); for (int i = 0; i < 3; ++i) T[i] += d[i]; }
  Q det = u[0] * (S[1] * T[2] - S[2] * T[1]) - u[1] * (S[0] * T[2] - S[2] * T[0]) + u[2] * (S[0] * T[1] - S[1] * T[0]);
  return -CGAL::sign(det);  // vol(R,a,b,F) = -det/6 (proofs/star_filter.md, L7)
}
}  // namespace

TEST(Predicates, StarSignIsExactWherePlainDoublesFail) {
  // Near-degenerate decomposition tets: R (the cell mean) within a few ulps of
  // the plane (a, b, F), far from the origin. The exact predicate must agree
  // with rational arithmetic every time; plain doubles must be caught wrong at
  // least once (otherwise this test does not exercise the filter).
  // Integer points on the plane 3x + 7y - 5z = 0 with coordinates ~1e7: every
  // difference is exact, but the determinant's products (~1e22) exceed 2^53,
  // so doubles round while the exact value is 0 (or +-small after a nudge).
  std::mt19937_64 rng(12345);
  std::uniform_int_distribution<long> coord(-2000000, 2000000);
  std::uniform_int_distribution<int> nudge(-1, 1);
  int wrong_double = 0, exact_path = 0;
  predicate_counters().reset();
  auto P = [&]() {
    const double x = 5.0 * double(coord(rng)), y = 5.0 * double(coord(rng));
    return Point3{x, y, (3 * x + 7 * y) / 5};  // exact: integers below 2^53
  };
  for (int trial = 0; trial < 5000; ++trial) {
    const Point3 a = P(), b = P();
    std::vector<Point3> face{a, b, P(), P()};
    std::vector<Point3> cell = face;
    for (int k = 0; k < 4; ++k) cell.push_back(P());
    cell.back().z += nudge(rng);  // exact sign 0, + or -
    const int truth = rational_star_sign(a, b, face, cell);
    const Sign exact = decomposition_tet_sign(a, b, face, cell);
    ASSERT_EQ(static_cast<int>(exact), truth) << "trial " << trial;
    // The summed filter (L9d) about the cell's first point and about a far
    // origin: the same exact sign.
    for (const Point3& o : {cell[0], Point3{1e7, -3e6, 2.5e5}}) {
      const PointSums fs = point_sums(face, o), cs = point_sums(cell, o);
      ASSERT_EQ(static_cast<int>(decomposition_tet_sign(a, b, face, cell, fs, cs)), truth) << "trial " << trial;
    }
    wrong_double += static_cast<int>(decomposition_tet_sign_inexact(a, b, face, cell)) != truth;
  }
  exact_path = int(predicate_counters().star_exact.load());
  EXPECT_GT(wrong_double, 0) << "no adversarial case found";
  EXPECT_GT(exact_path, 0);
  std::printf("plain doubles wrong in %d of 5000 near-degenerate cases; exact path taken %d times\n",
              wrong_double, exact_path);
}
