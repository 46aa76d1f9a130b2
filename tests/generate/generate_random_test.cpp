// Random classified meshes and Kuhn lattices (lib/generate/random_mesh.h): the
// inputs of the property tests must themselves be valid, deterministic meshes.
#include "generate/random_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "classify/classify.h"
#include "core/error.h"
#include "predicates/predicates.h"

namespace polydual {
namespace {

std::size_t non_positive_tets(const TetSoup& s) {
  std::size_t bad = 0;
  for (const auto& t : s.tets)
    if (orient3d(s.points[t[0]], s.points[t[1]], s.points[t[2]], s.points[t[3]]) != Sign::Positive)
      ++bad;
  return bad;
}

// Parameters cycling through every option combination as the seed runs.
RandomMeshParams params_for(std::uint64_t seed) {
  RandomMeshParams p;
  p.seed = seed;
  p.num_points = 20 + static_cast<int>(seed % 7) * 15;
  p.regions = 1 + static_cast<int>(seed % 2);
  p.fracture = (seed / 2) % 2 == 1;
  p.lattice_points = (seed / 4) % 3 == 0;
  return p;
}

TEST(GenerateRandom, TwoHundredSeedsArePositiveAndClassify) {
  std::size_t with_fracture_face = 0, fracture_runs = 0;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const RandomMeshParams p = params_for(seed);
    TetSoup s = random_classified_mesh(p);
    ASSERT_FALSE(s.tets.empty()) << "seed " << seed;
    ASSERT_EQ(s.tet_region.size(), s.tets.size());
    EXPECT_FALSE(s.full_classification);
    EXPECT_EQ(non_positive_tets(s), 0u) << "seed " << seed;
    ClassifiedTetMesh m;
    ASSERT_NO_THROW(m = classify(s)) << "seed " << seed;
    if (p.regions == 1) EXPECT_EQ(m.model().count(3), 1u) << "seed " << seed;
    if (p.fracture && !s.triangles.empty()) {
      ++fracture_runs;
      for (const auto& f : m.model().entities[2])
        if (f.regions.size() == 2 && f.regions[0] == f.regions[1]) {
          ++with_fracture_face;
          break;
        }
    }
  }
  // Fracture triangles exist in most fracture runs, and each gives a model
  // face with the same region on both sides.
  EXPECT_GT(fracture_runs, 50u);
  EXPECT_EQ(with_fracture_face, fracture_runs);
}

TEST(GenerateRandom, SameSeedSameMesh) {
  for (std::uint64_t seed : {1u, 7u, 12345u}) {
    RandomMeshParams p = params_for(seed);
    p.fracture = true;
    TetSoup a = random_classified_mesh(p), b = random_classified_mesh(p);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.tets, b.tets);
    EXPECT_EQ(a.tet_region, b.tet_region);
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    for (std::size_t i = 0; i < a.triangles.size(); ++i) EXPECT_EQ(a.triangles[i].v, b.triangles[i].v);
  }
  RandomMeshParams p;
  p.seed = 1;
  RandomMeshParams q = p;
  q.seed = 2;
  EXPECT_NE(random_classified_mesh(p).points, random_classified_mesh(q).points);
}

// The first 8 points are the box corners and the other points lie in the box;
// the hull is the box, so the tet volumes add up to 1.
TEST(GenerateRandom, FillsTheUnitBox) {
  RandomMeshParams p;
  p.seed = 99;
  p.num_points = 200;
  TetSoup s = random_classified_mesh(p);
  EXPECT_EQ(s.points.size(), 208u);
  double vol = 0;
  for (const auto& t : s.tets)
    vol += dot(cross(s.points[t[1]] - s.points[t[0]], s.points[t[2]] - s.points[t[0]]),
               s.points[t[3]] - s.points[t[0]]) / 6.0;
  EXPECT_NEAR(vol, 1.0, 1e-12);
  for (const auto& q : s.points)
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(q[c] >= 0.0 && q[c] <= 1.0);
}

TEST(GenerateRandom, RejectsBadParams) {
  RandomMeshParams p;
  p.regions = 3;
  EXPECT_THROW(random_classified_mesh(p), UsageError);
  p.regions = 1;
  p.num_points = -1;
  EXPECT_THROW(random_classified_mesh(p), UsageError);
  EXPECT_THROW(kuhn_lattice(3, 2, 2, 1, 1, 1, 2), UsageError);
  EXPECT_THROW(kuhn_lattice(0, 2, 2), UsageError);
}

TEST(GenerateRandom, KuhnLatticeCountsAndVolumes) {
  const int nx = 4, ny = 3, nz = 2;
  const double hx = 0.5, hy = 0.25, hz = 2.0;
  for (int regions : {1, 2}) {
    TetSoup s = kuhn_lattice(nx, ny, nz, hx, hy, hz, regions);
    ASSERT_EQ(s.tets.size(), static_cast<std::size_t>(6 * nx * ny * nz));
    EXPECT_EQ(s.points.size(), static_cast<std::size_t>((nx + 1) * (ny + 1) * (nz + 1)));
    EXPECT_EQ(non_positive_tets(s), 0u);
    for (const auto& t : s.tets) {
      const double v = dot(cross(s.points[t[1]] - s.points[t[0]], s.points[t[2]] - s.points[t[0]]),
                           s.points[t[3]] - s.points[t[0]]) / 6.0;
      EXPECT_NEAR(v, hx * hy * hz / 6.0, 1e-14);
    }
    // Conformal and a box: classify() finds the box's 8/12/6 model entities
    // (plus the interface plane x = 1 with two regions).
    ClassifiedTetMesh m = classify(s);
    EXPECT_EQ(m.model().count(3), static_cast<std::size_t>(regions));
    EXPECT_EQ(m.model().count(2), regions == 1 ? 6u : 11u);
    EXPECT_EQ(m.model().count(1), regions == 1 ? 12u : 20u);
    EXPECT_EQ(m.model().count(0), regions == 1 ? 8u : 12u);
  }
}

}  // namespace
}  // namespace polydual
