// Tests of lib/quality: the star-shaped test's convention, the corner condition
// numbers (formula repairs pinned by limits, proofs/quality.md), Q1/Q2 and stats.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <random>

#include "generate/hex_block.h"
#include "mesh/poly_mesh.h"
#include "predicates/predicates.h"
#include "quality/corner.h"
#include "quality/metrics.h"
#include "quality/star_verdict.h"
#include "quality/stencil.h"

namespace polydual {
namespace {


double kappa(Vec3 a, Vec3 b, Vec3 c) {
  const double e1[3] = {a.x, a.y, a.z}, e2[3] = {b.x, b.y, b.z}, e3[3] = {c.x, c.y, c.z};
  return corner_kappa(e1, e2, e3);
}
double kappa_mod_delta(Vec3 a, Vec3 b, Vec3 c, double delta) {
  const double e1[3] = {a.x, a.y, a.z}, e2[3] = {b.x, b.y, b.z}, e3[3] = {c.x, c.y, c.z};
  return corner_kappa_mod_delta(e1, e2, e3, delta);
}
double kappa_mod(Vec3 a, Vec3 b, Vec3 c, double V0, double cc = kDefaultDeltaC) {
  const double e1[3] = {a.x, a.y, a.z}, e2[3] = {b.x, b.y, b.z}, e3[3] = {c.x, c.y, c.z};
  return corner_kappa_mod(e1, e2, e3, V0, cc);
}

std::vector<double> corner_kappas(const PolyMesh& m, Metric metric) {
  const MeshStencil s = build_stencil(m);
  std::vector<double> out;
  for (std::uint32_t c = 0; c < s.num_cells(); ++c)
    for_each_corner<double>(s, c, metric, PointsPos{m.points.data()},
                            [&](const double* e1, const double* e2, const double* e3) {
                              out.push_back(corner_kappa(e1, e2, e3));
                            });
  return out;
}

TEST(StarTest, UnitCubeIsValidWith24Tets) {
  const PolyMesh cube = hex_block(1);
  const CellVerdict v = star_shaped_verdict(cube, CellId(0));
  EXPECT_TRUE(v.valid);
  EXPECT_EQ(v.total_tets, 24);
  EXPECT_EQ(v.bad_tets, 0);
}

TEST(StarTest, VertexPushedThroughOppositeFaceIsInvalid) {
  PolyMesh cube = hex_block(1);
  cube.points[7] = {0.5, 0.5, -0.5};  // (1,1,1) pushed through the face z = 0
  const CellVerdict v = star_shaped_verdict(cube, CellId(0));
  EXPECT_FALSE(v.valid);
  EXPECT_GT(v.bad_tets, 0);
  EXPECT_EQ(v.total_tets, 24);
}

TEST(StarTest, ReversedCellIsInvalidEverywhere) {
  // Mirror the cube: every face loop now has an inward normal.
  PolyMesh cube = hex_block(1);
  for (auto& p : cube.points) p.x = -p.x;
  const CellVerdict v = star_shaped_verdict(cube, CellId(0));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.bad_tets, 24);
}

TEST(StarTest, StencilAndMeshVerdictsAgree) {
  PolyMesh m = hex_block(3);
  m.points[21] = {2.6, 1.2, 0.8};  // interior point (1,1,1) pushed past its neighbours
  const auto all = star_shaped_verdicts(m);
  const MeshStencil s = build_stencil(m);
  std::vector<Point3> scratch;
  int invalid = 0;
  for (std::uint32_t c = 0; c < m.num_cells(); ++c) {
    const CellVerdict a = star_shaped_verdict(m, CellId(c));
    const CellVerdict b = star_shaped_verdict(s, c, m.points, false, scratch);
    EXPECT_EQ(a.valid, all[c].valid);
    EXPECT_EQ(a.bad_tets, all[c].bad_tets);
    EXPECT_EQ(a.valid, b.valid);
    EXPECT_EQ(a.bad_tets, b.bad_tets);
    EXPECT_EQ(a.total_tets, b.total_tets);
    invalid += !a.valid;
  }
  EXPECT_GT(invalid, 0);
  EXPECT_EQ(count_invalid_cells(s, m.points), static_cast<std::size_t>(invalid));
}

// The stencil's verdict decides most tets with the inline summed filter; where
// it cannot, the exact fallback must give the answer. A cube flattened to
// height 1e-300 is valid, but every tet's permanent is below the filter's
// range (all 24 go exact); a cube flattened to height 0 is invalid everywhere.
TEST(StarTest, StencilVerdictIsExactWhereTheSummedFilterCannotDecide) {
  const auto exact_now = [] { return predicate_counters().star_exact.load(); };
  std::vector<Point3> scratch;
  PolyMesh thin = hex_block(1);
  for (auto& p : thin.points) p.z *= 1e-300;
  const MeshStencil s = build_stencil(thin);
  const auto e0 = exact_now();
  const CellVerdict v = star_shaped_verdict(s, 0, thin.points, false, scratch);
  EXPECT_TRUE(v.valid);
  EXPECT_EQ(v.bad_tets, 0);
  EXPECT_EQ(v.total_tets, 24);
  EXPECT_GE(exact_now() - e0, 24u);
  PolyMesh flat = hex_block(1);
  for (auto& p : flat.points) p.z = 0;
  const CellVerdict f = star_shaped_verdict(s, 0, flat.points, false, scratch);
  EXPECT_FALSE(f.valid);
  EXPECT_EQ(f.bad_tets, 24);
  EXPECT_EQ(star_shaped_verdict(flat, CellId(0)).bad_tets, 24);
}

TEST(Corner, RightUnitCornerIsThree) {
  EXPECT_DOUBLE_EQ(kappa({1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 3.0);
  EXPECT_DOUBLE_EQ(kappa({2, 0, 0}, {0, 2, 0}, {0, 0, 2}), 3.0);
}

TEST(Corner, RegularTetCornerByHand) {
  // Unit edges at 60 degrees: |ei x ej|^2 = 3/4, A = 9/4, L = 3, V = 6 vol = 1/sqrt(2):
  // kappa = sqrt(27/4) sqrt(2) = 3 sqrt(6) / 2.
  const Vec3 a{1, 0, 0}, b{0.5, std::sqrt(3.0) / 2, 0}, c{0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0)};
  EXPECT_NEAR(kappa(a, b, c), 1.5 * std::sqrt(6.0), 1e-14);
}

// The repaired A and L (proofs/quality.md): kappa >= 3 for every valid corner and
// invariant under cyclic permutations of the edges. The extracted typos
// (A with e3 x e2 twice, L = 3|e1|^2) break both.
TEST(Corner, RepairedFormulaIsSymmetricAndBoundedBelowByThree) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  while (tested < 1000) {
    Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    if (dot(cross(a, b), c) < 1e-3) continue;
    ++tested;
    const double k = kappa(a, b, c);
    EXPECT_GE(k, 3.0 - 1e-12);
    EXPECT_NEAR(kappa(b, c, a) / k, 1.0, 1e-13);
    EXPECT_NEAR(kappa(c, a, b) / k, 1.0, 1e-13);
    // The typo L = 3|e1|^2 would give kappa < 3 on a short e1:
    const double typoL = 3 * norm2(a);
    double A, L, V;
    const double e1[3] = {a.x, a.y, a.z}, e2[3] = {b.x, b.y, b.z}, e3[3] = {c.x, c.y, c.z};
    corner_invariants(e1, e2, e3, A, L, V);
    EXPECT_DOUBLE_EQ(L, norm2(a) + norm2(b) + norm2(c));
    EXPECT_DOUBLE_EQ(A, norm2(cross(a, b)) + norm2(cross(b, c)) + norm2(cross(c, a)));
    (void)typoL;
  }
  const Vec3 a{0.1, 0, 0}, b{0, 1, 0}, c{0, 0, 1};
  EXPECT_LT(std::sqrt((norm2(cross(a, b)) + norm2(cross(b, c)) + norm2(cross(c, a))) * 3 * norm2(a)) /
                dot(cross(a, b), c),
            3.0);  // the typo's value: below the bound, so it cannot be the measure
}

TEST(Corner, KappaModTendsToKappaAsDeltaVanishes) {
  const Vec3 a{1, 0.2, 0}, b{0.1, 0.9, 0.3}, c{0.2, -0.1, 1.2};
  const double k = kappa(a, b, c);
  double prev = std::fabs(kappa_mod_delta(a, b, c, 1.0) - k);
  for (double delta : {1e-1, 1e-2, 1e-3, 1e-4, 1e-6}) {
    const double err = std::fabs(kappa_mod_delta(a, b, c, delta) - k);
    EXPECT_LT(err, prev);
    prev = err;
  }
  EXPECT_NEAR(kappa_mod_delta(a, b, c, 1e-8) / k, 1.0, 1e-14);
  // The adaptive delta vanishes as V/V0 grows: kappa_mod -> kappa.
  const double V = dot(cross(a, b), c);
  EXPECT_NEAR(kappa_mod(a, b, c, V / 20) / k, 1.0, 1e-12);
  EXPECT_NEAR(kappa_mod(a, b, c, V) / k, 1.0, 1e-4);
}

TEST(Corner, AdaptiveDeltaLimitsAndUnits) {
  const double V0 = 2.5;
  EXPECT_NEAR(adaptive_delta(0.0, V0, 50) , V0 / 51, 1e-15);
  EXPECT_NEAR(adaptive_delta(-1e6, V0, 50), V0, 1e-12);  // tangled: delta -> V0
  EXPECT_EQ(adaptive_delta(1e6, V0, 50), 0.0);             // no overflow, -> 0
  // delta scales like V (so kappa_mod is scale invariant): delta(s^3 V; s^3 V0) = s^3 delta(V; V0).
  EXPECT_NEAR(adaptive_delta(0.7 * 8, V0 * 8, 50), 8 * adaptive_delta(0.7, V0, 50), 1e-14);
}

TEST(Corner, KappaModFiniteAndSmoothThroughZeroVolume) {
  // e3 = (0.3, 0.2, t): V = t. kappa_mod and its derivative are continuous
  // through t = 0 and finite for t < 0 (the untangling barrier is finite).
  const double V0 = 0.2, h = 1e-3;
  auto f = [&](double t) { return kappa_mod({1, 0, 0}, {0, 1, 0}, {0.3, 0.2, t}, V0); };
  auto df = [&](double t) {
    ceres::Jet<double, 1> e1[3] = {ceres::Jet<double, 1>(1.0), ceres::Jet<double, 1>(0.0), ceres::Jet<double, 1>(0.0)};
    ceres::Jet<double, 1> e2[3] = {ceres::Jet<double, 1>(0.0), ceres::Jet<double, 1>(1.0), ceres::Jet<double, 1>(0.0)};
    ceres::Jet<double, 1> e3[3] = {ceres::Jet<double, 1>(0.3), ceres::Jet<double, 1>(0.2), ceres::Jet<double, 1>(t, 0)};
    return corner_kappa_mod(e1, e2, e3, V0, kDefaultDeltaC).v[0];
  };
  for (double t = -0.5; t <= 0.5; t += h) {
    const double v = f(t), d = df(t);
    ASSERT_TRUE(std::isfinite(v) && v > 0) << t;
    ASSERT_TRUE(std::isfinite(d)) << t;
    // Exact (Jet) derivative matches central differences everywhere, incl. V = 0.
    const double fd = (f(t + 1e-6) - f(t - 1e-6)) / 2e-6;
    EXPECT_NEAR(fd, d, 1e-5 * std::max(1.0, std::fabs(d))) << t;
  }
  // The derivative is continuous at V = 0 (where regularised_volume switches
  // branch): the one-sided gap shrinks linearly with the distance.
  double prev_gap = std::fabs(df(1e-4) - df(-1e-4));
  for (double eps : {1e-5, 1e-6, 1e-7, 1e-8}) {
    const double gap = std::fabs(df(eps) - df(-eps));
    EXPECT_LT(gap, 0.2 * prev_gap) << eps;
    prev_gap = gap;
  }
  EXPECT_LT(prev_gap, 1e-4 * std::fabs(df(0.0)));
  // Decreasing towards valid: the barrier pushes V up.
  EXPECT_LT(df(0.0), 0.0);
  EXPECT_GT(f(-0.1), f(0.0));
  EXPECT_GT(f(0.0), f(0.1));
}

TEST(Corner, AdjointGradientMatchesJet) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int it = 0; it < 200; ++it) {
    const Vec3 e[3] = {{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    const double V0 = 0.1 + std::fabs(u(rng));
    Vec3 g[3];
    const double val = corner_kappa_mod_gradient(e[0], e[1], e[2], V0, 50, g[0], g[1], g[2]);
    using J = ceres::Jet<double, 9>;
    J je[3][3];
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d) je[i][d] = J(e[i][d], 3 * i + d);
    const J r = corner_kappa_mod(je[0], je[1], je[2], V0, 50.0);
    EXPECT_NEAR(val, r.a, 1e-12 * r.a);
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(g[i][d], r.v[3 * i + d], 1e-9 * (1 + std::fabs(r.v[3 * i + d])));
  }
}

// design §6's cube check, done honestly: Q2's corners on a unit cube are NOT right
// corners (e3 points to the cell centre): edges (0,1,0), (1,0,0), (.5,.5,-.5)
// give A = 2, L = 2.75, V = 0.5, kappa = 2 sqrt(5.5). Q1's corner at a of tet
// (a,b,F,R): (F-a, b-a, R-a) = ((.5,.5,0), (1,0,0), (.5,.5,-.5)) gives
// A = 0.875, L = 2.25, V = 0.25, kappa = sqrt(1.96875)/0.25.
TEST(Metrics, UnitCubeCornerValues) {
  const PolyMesh cube = hex_block(1);
  const auto q2 = corner_kappas(cube, Metric::Q2);
  ASSERT_EQ(q2.size(), 24u);  // 6 faces x 4 vertices (paper: 3 per vertex x 8 = 24)
  for (double k : q2) EXPECT_NEAR(k, 2 * std::sqrt(5.5), 1e-13);
  const auto q1 = corner_kappas(cube, Metric::Q1);
  ASSERT_EQ(q1.size(), 48u);  // 24 decomposition tets x 2 original-vertex corners
  for (double k : q1) EXPECT_NEAR(k, std::sqrt(1.96875) / 0.25, 1e-13);
  const MeshStencil s = build_stencil(cube);
  EXPECT_NEAR(cell_quality(s, 0, Metric::Q2, cube.points), 2 * std::sqrt(5.5) / 3, 1e-13);
  EXPECT_NEAR(cell_quality(s, 0, Metric::Q1, cube.points), std::sqrt(1.96875) / 0.75, 1e-13);
}

TEST(Metrics, CubeIsALocalOptimumOfItsCellEnergy) {
  // Moving one cube vertex in any direction does not lower the summed corner
  // kappa of Q1 or Q2 (the measures reward the cube, though not with value 1).
  const PolyMesh cube = hex_block(1);
  const MeshStencil s = build_stencil(cube);
  for (Metric m : {Metric::Q1, Metric::Q2}) {
    const auto V0 = cell_reference_volumes(s, m, cube.points);
    const double e0 = cell_energy(s, 0, m, cube.points, V0[0], 50);
    for (int d = 0; d < 3; ++d)
      for (double sgn : {-1.0, 1.0}) {
        PolyMesh moved = cube;
        moved.points[7][d] += sgn * 1e-3;
        EXPECT_GT(cell_energy(s, 0, m, moved.points, V0[0], 50), e0);
      }
  }
}

TEST(Metrics, InvariantUnderScalingRotationTranslation) {
  PolyMesh m = hex_block(2);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  for (auto& p : m.points) p += Vec3{u(rng), u(rng), u(rng)};
  const MeshStencil s = build_stencil(m);
  // Rotation about (1,2,3)/|.| by 0.7 rad (Rodrigues), scale 3.7, shift.
  const Vec3 axis = Vec3{1, 2, 3} / std::sqrt(14.0);
  const double th = 0.7, sc = 3.7;
  const Vec3 shift{10, -4, 2.5};
  std::vector<Point3> moved;
  for (const auto& p : m.points) {
    const Vec3 r = std::cos(th) * p + std::sin(th) * cross(axis, p) + (1 - std::cos(th)) * dot(axis, p) * axis;
    moved.push_back(sc * r + shift);
  }
  for (Metric metric : {Metric::Q1, Metric::Q2}) {
    const auto qa = cell_qualities(s, metric, m.points);
    const auto qb = cell_qualities(s, metric, moved);
    const auto va = cell_reference_volumes(s, metric, m.points);
    const auto vb = cell_reference_volumes(s, metric, moved);
    for (std::uint32_t c = 0; c < s.num_cells(); ++c) {
      EXPECT_NEAR(qa[c] / qb[c], 1.0, 1e-12);
      EXPECT_NEAR(vb[c] / (va[c] * sc * sc * sc), 1.0, 1e-12);
      EXPECT_NEAR(cell_energy(s, c, metric, m.points, va[c], 50) / cell_energy(s, c, metric, moved, vb[c], 50),
                  1.0, 1e-12);
    }
  }
}

// The fused pass of the optimiser's records gives both values bit for bit,
// on valid and on tangled cells (a point pushed far through its cell).
TEST(Metrics, EnergyAndQualityInOnePassAreTheSeparateValues) {
  PolyMesh m = hex_block(3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (auto& p : m.points) p += Vec3{u(rng), u(rng), u(rng)};
  m.points[m.points.size() / 2] += Vec3{1.5, -1.2, 0.9};
  const MeshStencil s = build_stencil(m);
  std::size_t tangled = 0;
  for (Metric metric : {Metric::Q1, Metric::Q2}) {
    const auto V0 = cell_reference_volumes(s, metric, m.points);
    for (std::uint32_t c = 0; c < s.num_cells(); ++c) {
      double q = -1;
      const double e = cell_energy_and_quality(s, c, metric, m.points, V0[c], 50, &q);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(e), std::bit_cast<std::uint64_t>(cell_energy(s, c, metric, m.points, V0[c], 50)));
      EXPECT_EQ(std::bit_cast<std::uint64_t>(q), std::bit_cast<std::uint64_t>(cell_quality(s, c, metric, m.points)));
      tangled += std::isinf(q);
    }
  }
  EXPECT_GT(tangled, 0u);  // the tangled branch was exercised
}

TEST(Metrics, StatsAndJson) {
  PolyMesh m = hex_block(3);
  m.points[21] = {2.6, 1.2, 0.8};
  const QualityStats st = quality_stats(m, Metric::Q1);
  EXPECT_EQ(st.cells, 27u);
  EXPECT_GT(st.tangled, 0u);
  std::size_t counted = 0;
  for (auto h : st.histogram) counted += h;
  EXPECT_EQ(counted + st.tangled, st.cells);
  EXPECT_LE(st.min, st.mean);
  EXPECT_LE(st.mean, st.max);
  EXPECT_GE(st.min, 1.0);
  const std::string js = st.to_json().dump();
  for (const char* key : {"\"metric\"", "\"tangled\"", "\"histogram\"", "\"bin_edges\"", "\"mean\""})
    EXPECT_NE(js.find(key), std::string::npos) << key;
  // Q1 tangled <=> star-invalid on this (non-degenerate) configuration.
  const auto v = star_shaped_verdicts(m);
  EXPECT_EQ(static_cast<std::size_t>(std::count_if(v.begin(), v.end(), [](auto x) { return !x.valid; })),
            st.tangled);
}

}  // namespace
}  // namespace polydual
