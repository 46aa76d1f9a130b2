// The face-flatness term of the local optimiser (optim/planarity.h): its value is OpenFOAM's flatness deficit of the faces around the
// point (quality/flatness.h), and a positive weight makes the faces flatter
// without giving up the exact validity guarantee.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.h"
#include "generate/random_mesh.h"
#include "optim/planarity.h"
#include "pipeline/convert.h"
#include "quality/flatness.h"
#include "quality/stencil.h"

namespace polydual {
namespace {

ConvertResult raw_dual() {
  RandomMeshParams p;
  p.seed = 7;
  p.num_points = 80;
  p.regions = 2;
  PipelineParams params;
  params.optim.method = OptimParams::Method::None;
  params.split.enabled = false;
  return convert(random_classified_mesh(p), params);
}

// value(x = p's own position) == sum over the loops of p's cells holding p of
// n * (1 - flatness), flatness by face_flatness; moving p changes it.
TEST(Planarity, TermIsTheFlatnessDeficitOfTheFacesAroundThePoint) {
  const ConvertResult r = raw_dual();
  const MeshStencil s = build_stencil(r.mesh);
  const Point3* pts = r.mesh.points.data();
  std::size_t checked = 0;
  for (std::uint32_t pi = 0; pi < r.mesh.num_points(); pi += 7) {
    const PointId p(pi);
    optim_detail::PlanarityTerm term;
    term.build(s, p);
    double expect = 0;
    for (std::uint32_t c : s.cells_of(p))
      for (std::uint32_t j = s.cell_loop_off[c]; j < s.cell_loop_off[c + 1]; ++j) {
        const auto loop = s.loop(j);
        bool has = false;
        std::vector<Point3> poly;
        for (PointId q : loop) {
          has = has || q == p;
          poly.push_back(pts[q.idx]);
        }
        if (has) expect += double(loop.size()) * (1.0 - face_flatness(poly).flatness);
      }
    EXPECT_NEAR(term.value(s, pts, pts[pi]), expect, 1e-9 * (1 + expect)) << "point " << pi;
    if (!term.empty()) {
      ++checked;
      const Point3 moved = pts[pi] + Point3{1e-2, -2e-2, 3e-2};
      EXPECT_NE(term.value(s, pts, moved), term.value(s, pts, pts[pi]));
    }
  }
  EXPECT_GT(checked, 10u);
}

double mean_flatness(const ConvertResult& r) {
  const MeshStencil s = build_stencil(r.mesh);
  double sum = 0;
  for (std::size_t f = 0; f < r.mesh.num_faces(); ++f) {
    std::vector<Point3> poly;
    for (PointId q : r.mesh.face(FaceId(f))) poly.push_back(r.mesh.points[q.idx]);
    sum += face_flatness(poly).flatness;
  }
  return sum / double(r.mesh.num_faces());
}

TEST(Planarity, WeightMakesFacesFlatterAndKeepsValidity) {
  RandomMeshParams mp;
  mp.seed = 3;
  mp.num_points = 70;
  const TetSoup soup = random_classified_mesh(mp);
  PipelineParams a;
  PipelineParams b = a;
  b.optim.planarity = 20;
  const ConvertResult ra = convert(soup, a), rb = convert(soup, b);
  EXPECT_LE(rb.report.invalid_after, ra.report.invalid_after);
  EXPECT_EQ(rb.check.invalid_cells, rb.report.invalid_after);  // the exact verdicts of the written mesh
  EXPECT_GT(mean_flatness(rb), mean_flatness(ra));
  PipelineParams g;
  g.optim.method = OptimParams::Method::Global;
  g.optim.planarity = 1;
  EXPECT_THROW(convert(soup, g), UsageError);
  g.optim.method = OptimParams::Method::Local;
  g.optim.planarity = -1;
  EXPECT_THROW(convert(soup, g), UsageError);
}

}  // namespace
}  // namespace polydual

namespace polydual {
namespace {

// optimize()'s seed_cells: a valid mesh re-optimised from a few seed cells
// visits only around them in the first sweep (all points without seeds), an
// all-zero seed visits nothing, and the exact guarantee holds either way.
TEST(OptimSeed, SeededSmoothingStartsAtTheSeedCells) {
  RandomMeshParams mp;
  mp.seed = 5;
  mp.num_points = 80;
  const ConvertResult r = convert(random_classified_mesh(mp), PipelineParams{});  // valid (split), smoothed
  ASSERT_EQ(r.check.invalid_cells, 0u);
  OptimParams one;
  one.max_iter = 1;
  PolyMesh full = r.mesh, seeded = r.mesh, none = r.mesh;
  const OptimReport a = optimize(full, nullptr, one);
  std::vector<char> seed(r.mesh.num_cells(), 0);
  seed[0] = seed[1] = 1;
  const OptimReport b = optimize(seeded, nullptr, one, {}, seed);
  const OptimReport c = optimize(none, nullptr, one, {}, std::vector<char>(r.mesh.num_cells(), 0));
  ASSERT_EQ(a.invalid_before, 0);
  ASSERT_GE(a.iterations.size(), 2u);
  ASSERT_GE(b.iterations.size(), 2u);
  EXPECT_GT(b.iterations[1].visited, 0u);
  EXPECT_LT(b.iterations[1].visited, a.iterations[1].visited);
  EXPECT_EQ(c.iterations.size() >= 2 ? c.iterations[1].visited : 0u, 0u);
  EXPECT_EQ(b.invalid_after, 0);
  EXPECT_THROW(optimize(none, nullptr, one, {}, std::vector<char>(3, 1)), UsageError);
}

}  // namespace
}  // namespace polydual
