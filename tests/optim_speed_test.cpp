// Tests of the fast paths of lib/optim (issue 14): the lagged local objective
// (centres held during a visit) and Method::Untangle.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "generate/hex_block.h"
#include "optim/lagged_objective.h"
#include "optim/objective.h"
#include "optim/optimize.h"
#include "quality/metrics.h"
#include "quality/star_verdict.h"
#include "quality/stencil.h"

namespace polydual {
namespace {

PolyMesh jittered_block(int n, double amp, unsigned seed) {
  PolyMesh m = hex_block(n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amp, amp);
  for (std::size_t i = 0; i < m.num_points(); ++i)
    if (m.point_class[i].dim == 3) m.points[i] += Vec3{u(rng), u(rng), u(rng)};
  return m;
}

// A block with one interior point pushed through a face: invalid cells to untangle.
PolyMesh tangled_block() {
  PolyMesh m = jittered_block(6, 0.2, 33);
  m.points[(2 * 7 + 2) * 7 + 2] = {3.4, 2.2, 1.8};
  return m;
}

std::vector<std::uint8_t> valid_flags(const PolyMesh& m) {
  const MeshStencil s = build_stencil(m);
  std::vector<std::uint8_t> v(m.num_cells());
  std::vector<Point3> scratch;
  for (std::uint32_t c = 0; c < v.size(); ++c) v[c] = star_shaped_verdict(s, c, m.points, true, scratch).valid;
  return v;
}

TEST(OptimSpeed, LaggedDerivativesMatchDifferencesOfTheLaggedValue) {
  for (Metric metric : {Metric::Q1, Metric::Q2}) {
    const PolyMesh m = jittered_block(3, 0.15, 7);
    const MeshStencil s = build_stencil(m);
    const std::vector<double> V0 = cell_reference_volumes(s, metric, m.points);
    const PointId p(21);  // interior grid point (1,1,1): 8 cells
    LaggedObjective lag;
    lag.build(s, m.points.data(), V0.data(), metric, p);
    // Q1: 4 corners per (cell, face of p); Q2: 3. A point of the hex grid has
    // 3 faces in each of its 8 cells.
    EXPECT_EQ(lag.num_corners(), (metric == Metric::Q1 ? 4u : 3u) * 3u * 8u);
    double g[3], H[9];
    const Point3 x0 = m.points[p.idx];
    const double f0 = lag.derivatives(x0, kDefaultDeltaC, g, H);
    EXPECT_EQ(f0, lag.value(x0, kDefaultDeltaC));
    const double h = 1e-5;
    for (int i = 0; i < 3; ++i) {
      Point3 xp = x0, xm = x0;
      xp[i] += h;
      xm[i] -= h;
      const double fp = lag.value(xp, kDefaultDeltaC), fm = lag.value(xm, kDefaultDeltaC);
      EXPECT_NEAR(g[i], (fp - fm) / (2 * h), 1e-5 * (1 + std::fabs(g[i])));
      double gp[3], gm[3], Hs[9];
      lag.derivatives(xp, kDefaultDeltaC, gp, Hs);
      lag.derivatives(xm, kDefaultDeltaC, gm, Hs);
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(H[3 * j + i], (gp[j] - gm[j]) / (2 * h), 1e-4 * (1 + std::fabs(H[3 * j + i])));
    }
    // The direct corners are a strict part of the exact local objective, and
    // their gradient is the exact one less the centres' share, which is small:
    // both pull p the same way on a jittered grid.
    const LocalObjective exact{s, m.points.data(), V0.data(), metric, kDefaultDeltaC, p};
    const double xa[3] = {x0.x, x0.y, x0.z};
    EXPECT_LT(f0, exact(xa));
    double ge[3], He[9];
    local_objective_derivatives(s, m.points.data(), V0.data(), metric, kDefaultDeltaC, p, ge, He);
    EXPECT_GT(g[0] * ge[0] + g[1] * ge[1] + g[2] * ge[2], 0);
  }
}

TEST(OptimSpeed, LaggedValueIsTranslationInvariantAndDependsOnThePoint) {
  // The held corner edges are relative to the held points and centres: moving
  // the whole mesh by d (and building again) leaves the value unchanged, while
  // moving p alone changes it.
  const PolyMesh m = jittered_block(3, 0.15, 9);
  const MeshStencil s = build_stencil(m);
  const std::vector<double> V0 = cell_reference_volumes(s, Metric::Q1, m.points);
  const PointId p(21);
  LaggedObjective lag;
  lag.build(s, m.points.data(), V0.data(), Metric::Q1, p);
  PolyMesh shifted = m;
  const Vec3 d{0.05, -0.03, 0.02};
  for (auto& x : shifted.points) x += d;
  LaggedObjective lag2;
  lag2.build(s, shifted.points.data(), V0.data(), Metric::Q1, p);
  EXPECT_NEAR(lag.value(m.points[p.idx], kDefaultDeltaC), lag2.value(shifted.points[p.idx], kDefaultDeltaC), 1e-9);
  EXPECT_GT(std::fabs(lag.value(m.points[p.idx] + d, kDefaultDeltaC) - lag.value(m.points[p.idx], kDefaultDeltaC)), 1e-6);
}

TEST(OptimSpeed, LaggedAndUntangleKeepValidCellsValidAndUntangle) {
  for (auto method : {OptimParams::Method::Local, OptimParams::Method::Untangle}) {
    PolyMesh m = tangled_block();
    const std::vector<std::uint8_t> before = valid_flags(m);
    OptimParams p;
    p.method = method;
    p.derivatives = OptimParams::Derivatives::Lagged;
    const OptimReport r = optimize(m, nullptr, p);
    EXPECT_GT(r.invalid_before, 0);
    EXPECT_EQ(r.invalid_after, 0);
    const std::vector<std::uint8_t> after = valid_flags(m);
    for (std::size_t c = 0; c < after.size(); ++c)
      if (before[c]) EXPECT_TRUE(after[c]) << "cell " << c << " became invalid";
    EXPECT_EQ(static_cast<std::size_t>(r.invalid_after),
              std::count(after.begin(), after.end(), std::uint8_t{0}));
    if (method == OptimParams::Method::Untangle) {
      // Untangling only: it stops at the first sweep without invalid cells.
      ASSERT_GE(r.iterations.size(), 2u);
      EXPECT_EQ(r.iterations.back().invalid, 0u);
      for (std::size_t i = 1; i + 1 < r.iterations.size(); ++i) EXPECT_GT(r.iterations[i].invalid, 0u);
    }
  }
}

TEST(OptimSpeed, UntangleDoesNothingOnAValidMesh) {
  PolyMesh m = jittered_block(4, 0.1, 5);
  const PolyMesh start = m;
  OptimParams p;
  p.method = OptimParams::Method::Untangle;
  const OptimReport r = optimize(m, nullptr, p);
  EXPECT_EQ(r.invalid_before, 0);
  EXPECT_EQ(r.iterations.size(), 1u);
  EXPECT_EQ(m.points, start.points);
}

TEST(OptimSpeed, LaggedAndUntangleAreIdenticalForOneAndTwoThreads) {
  for (auto method : {OptimParams::Method::Local, OptimParams::Method::Untangle}) {
    OptimParams p;
    p.method = method;
    p.derivatives = OptimParams::Derivatives::Lagged;
    p.max_iter = 5;
    PolyMesh a = tangled_block(), b = a;
    OptimReport ra, rb;
    {
      tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
      ra = optimize(a, nullptr, p);
    }
    {
      tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
      rb = optimize(b, nullptr, p);
    }
    EXPECT_GT(ra.vertex_updates, 0u);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(ra.vertex_updates, rb.vertex_updates);
  }
}

TEST(OptimSpeed, ParsersKnowTheNewNames) {
  EXPECT_EQ(parse_method("untangle"), OptimParams::Method::Untangle);
  EXPECT_STREQ(method_name(OptimParams::Method::Untangle), "untangle");
  EXPECT_EQ(parse_derivatives("lagged"), OptimParams::Derivatives::Lagged);
  EXPECT_STREQ(derivatives_name(OptimParams::Derivatives::Lagged), "lagged");
}

}  // namespace
}  // namespace polydual
