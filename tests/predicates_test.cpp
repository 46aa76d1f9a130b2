// lib/predicates: sign conventions and exactness against rational arithmetic.
#include <gtest/gtest.h>

#include <CGAL/Gmpq.h>

#include <random>
#include <vector>

#include "predicates/predicates.h"

using namespace polydual;

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
    wrong_double += static_cast<int>(decomposition_tet_sign_inexact(a, b, face, cell)) != truth;
  }
  exact_path = int(predicate_counters().star_exact.load());
  EXPECT_GT(wrong_double, 0) << "no adversarial case found";
  EXPECT_GT(exact_path, 0);
  std::printf("plain doubles wrong in %d of 5000 near-degenerate cases; exact path taken %d times\n",
              wrong_double, exact_path);
}
