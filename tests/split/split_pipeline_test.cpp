// The split loop in the pipeline (split/split.h, proofs/split.md): the domains
// with slit cells and random classified meshes end with every cell valid by
// the exact star test, the dual still passes validate(), and each cell records
// the uncut cell it came from.
#include <gtest/gtest.h>

#include <cstdlib>

#include "core/error.h"
#include "generate/domains.h"
#include "generate/random_mesh.h"
#include "pipeline/convert.h"

namespace polydual {
namespace {

// Every cell's origin is a cell of the uncut dual of the same primal vertex.
void expect_origins(const ConvertResult& r, const PolyMesh& uncut) {
  ASSERT_EQ(r.mesh.cell_origin.size(), r.mesh.num_cells());
  for (std::size_t c = 0; c < r.mesh.num_cells(); ++c) {
    const CellId o = r.mesh.cell_origin[c];
    ASSERT_LT(o.idx, uncut.num_cells());
    EXPECT_EQ(uncut.cell_primal[o.idx], r.mesh.cell_primal[c]);
    EXPECT_EQ(uncut.cell_material[o.idx], r.mesh.cell_material[c]);
  }
}

void domain_ends_valid(Domain d, bool expect_cuts) {
  const TetSoup soup = generate_domain(d, 5000);
  PipelineParams no_split;
  no_split.split.enabled = false;
  const ConvertResult plain = convert(soup, no_split);
  const ConvertResult r = convert(soup, PipelineParams{});
  EXPECT_EQ(r.report.invalid_after, 0u) << domain_name(d);
  EXPECT_EQ(r.check.invalid_cells, 0u);
  EXPECT_TRUE(r.check.validation.ok()) << domain_name(d);
  EXPECT_EQ(r.check.validation.slit_cells, 0u);
  ASSERT_NE(r.report.stage("split"), nullptr);
  EXPECT_EQ(plain.report.stage("split"), nullptr);
  EXPECT_TRUE(plain.mesh.cell_origin.empty());
  if (expect_cuts) {
    EXPECT_GT(plain.check.validation.slit_cells, 0u);  // what the split repairs
    EXPECT_GT(plain.report.invalid_after, 0u);
    EXPECT_GT(r.mesh.num_cells(), plain.mesh.num_cells());
    expect_origins(r, plain.mesh);
  }
}

TEST(SplitPipeline, FractureEndsValid) { domain_ends_valid(Domain::Fracture, true); }
TEST(SplitPipeline, TwoMatEndsValid) { domain_ends_valid(Domain::TwoMat, false); }

// Without the optimiser the rounds must do the work alone (Fichera's concave
// edges and corner): every cell ends valid, and one round is not enough (the
// barycentric points disturb neighbours, cut whole in the next rounds).
TEST(SplitPipeline, RoundsAloneEndValid) {
  const TetSoup soup = generate_domain(Domain::Fichera, 3000);
  PipelineParams p;
  p.optim.method = OptimParams::Method::None;
  const ConvertResult r = convert(soup, p);
  p.split.max_rounds = 1;
  const ConvertResult one = convert(soup, p);
  p.split.enabled = false;
  const ConvertResult plain = convert(soup, p);
  ASSERT_GT(plain.report.invalid_after, 0u);
  EXPECT_EQ(r.report.invalid_after, 0u);
  EXPECT_LE(one.report.invalid_after, plain.report.invalid_after);
  ASSERT_NE(r.report.stage("split"), nullptr);
  EXPECT_NO_THROW(r.report.stage("split")->stats.find("rounds")->at(1));  // two rounds or more ran
  EXPECT_TRUE(r.check.validation.ok());
  EXPECT_GT(r.mesh.num_cells(), plain.mesh.num_cells());
}

TEST(SplitPipeline, RequireValidNamesEachCell) {
  const TetSoup soup = generate_domain(Domain::Fichera, 3000);
  PipelineParams p;
  p.optim.method = OptimParams::Method::None;
  p.split.max_rounds = 0;
  p.split.require_valid = true;
  try {
    convert(soup, p);
    FAIL() << "invalid cells accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("remain invalid"), std::string::npos) << what;
    EXPECT_NE(what.find("cell "), std::string::npos);
    EXPECT_NE(what.find("vertex "), std::string::npos);
    EXPECT_NE(what.find("class dim "), std::string::npos);
  }
  p.split.max_rounds = SplitParams::kMaxRounds + 1;
  EXPECT_THROW(convert(soup, p), UsageError);
}

// The family of random mesh i: plain, two materials, one fracture, crossing
// sheets, a network of three, fins on the walls, a notch (concave edges and
// corner), lattice points (cospherical and coplanar points), mixes, and three
// materials touching along edges (edges of several chains).
constexpr int kFamilies = 11;
RandomMeshParams random_family(int i) {
  RandomMeshParams p;
  p.seed = std::uint64_t(i);
  p.num_points = 20 + (i % 9) * 5;
  switch (i % kFamilies) {
    case 0: break;
    case 1: p.regions = 2; break;
    case 2: p.fracture = true; break;
    case 3: p.fracture = p.crossing_sheet = true; break;
    case 4: p.network = true; break;
    case 5: p.fins = true; break;
    case 6: p.notch = true; break;
    case 7: p.notch = p.fracture = true; p.regions = 2; break;
    case 8: p.lattice_points = p.fracture = true; break;
    case 9: p.network = p.fins = p.notch = true; break;
    default: p.touching = true; break;
  }
  return p;
}

// The split's property: on >= 1000 random classified meshes (every family
// above; POLYDUAL_SPLIT_MESHES overrides the count) the split loop alone,
// without the optimiser, ends with every cell valid by the exact star test,
// and the dual stays a valid one: closed cells, no face error, no slit, every
// model entity represented, the per-material volumes of the primal
// (validate(), proofs/dual_cuts.md), each cell's origin an uncut cell of the
// same vertex and material. Mutations that break it: whole vertices placed at
// the circumcentres (38 % of the corners valid), merges across them kept.
TEST(SplitPipeline, RandomMeshesEndWithEveryCellValid) {
  const char* env = std::getenv("POLYDUAL_SPLIT_MESHES");
  const int count = env ? std::atoi(env) : 1000;
  PipelineParams p;
  p.optim.method = OptimParams::Method::None;
  PipelineParams plain_p = p;
  plain_p.split.enabled = false;
  std::size_t split_meshes = 0, invalid_unsplit = 0;
  for (int i = 0; i < count; ++i) {
    const RandomMeshParams mp = random_family(i);
    const TetSoup soup = random_classified_mesh(mp);
    const ConvertResult r = convert(soup, p);
    ASSERT_EQ(r.check.invalid_cells, 0u) << "mesh " << i << " family " << i % kFamilies;
    EXPECT_EQ(r.report.invalid_after, 0u);
    EXPECT_TRUE(r.check.validation.ok()) << "mesh " << i << " family " << i % kFamilies;
    EXPECT_EQ(r.check.validation.closed_cells, r.check.validation.cells) << "mesh " << i;
    EXPECT_EQ(r.check.validation.slit_cells, 0u) << "mesh " << i;
    EXPECT_TRUE(r.check.validation.missing_model_entities.empty()) << "mesh " << i;
    if (i % 25 == 0 || !r.mesh.cell_origin.empty()) {
      const ConvertResult plain = convert(soup, plain_p);
      invalid_unsplit += plain.report.invalid_after;
      if (!r.mesh.cell_origin.empty()) {
        ++split_meshes;
        expect_origins(r, plain.mesh);
      }
    }
  }
  // The property is not vacuous: the unsplit duals have invalid cells.
  if (count >= 100) {
    EXPECT_GT(split_meshes, std::size_t(count) / 2);
    EXPECT_GT(invalid_unsplit, std::size_t(count));
  }
}

// With the default optimiser too: every cell valid, and the optimiser never
// makes the split mesh worse than the split alone.
TEST(SplitPipeline, RandomMeshesOptimisedEndValid) {
  for (int i = 0; i < kFamilies; ++i) {
    const TetSoup soup = random_classified_mesh(random_family(i));
    const ConvertResult r = convert(soup, PipelineParams{});
    EXPECT_EQ(r.check.invalid_cells, 0u) << "mesh " << i << " family " << i % kFamilies;
    EXPECT_TRUE(r.check.validation.ok()) << "mesh " << i;
  }
}

}  // namespace
}  // namespace polydual
