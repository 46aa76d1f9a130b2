// The split as a stage of its own (split/split.h): a driver other than the
// pipeline (here the test, later a distributed one) that calls begin_split,
// builds and checks the first dual itself and then run_split gets the very
// mesh convert() returns, point for point; and the optimiser reaches the
// loop only through the callback it is given (untangling in the rounds, the
// full method once on the mesh kept).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "classify/classify.h"
#include "dual/build_dual.h"
#include "pipeline/convert.h"
#include "split/coarsen.h"
#include "split/split.h"
#include "split_random_meshes.h"

namespace polydual {
namespace {

// Bitwise equality of the points and of the cells' faces and primal vertices.
void expect_same_mesh(const PolyMesh& a, const PolyMesh& b, const std::string& what) {
  ASSERT_EQ(a.num_points(), b.num_points()) << what;
  ASSERT_EQ(a.num_cells(), b.num_cells()) << what;
  ASSERT_EQ(a.num_faces(), b.num_faces()) << what;
  EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), a.num_points() * sizeof(Point3)), 0) << what;
  EXPECT_EQ(a.face_offsets, b.face_offsets) << what;
  EXPECT_EQ(a.face_points, b.face_points) << what;
  EXPECT_EQ(a.cell_offsets, b.cell_offsets) << what;
  EXPECT_EQ(a.cell_primal, b.cell_primal) << what;
  EXPECT_EQ(a.cell_origin, b.cell_origin) << what;
}

// The split driven by hand, without an optimiser: the first dual with the
// free-edge cuts, its exact verdicts, then run_split.
struct Driven {
  ClassifiedTetMesh primal;
  PolyMesh mesh;
  CheckResult check;
  Json stats;
  SplitState st;
};
Driven drive_split(const TetSoup& soup, const PipelineParams& p, const SplitHooks& hooks) {
  Driven d;
  d.primal = classify(soup, p.classify);
  SplitState& st = d.st;
  st = begin_split(d.primal);
  EXPECT_EQ(st.cuts.num_vertices_cut(), st.free_edge.num_vertices_cut());
  d.mesh = build_dual(d.primal, p.dual, nullptr, st.free_edge.empty() ? nullptr : &st.free_edge);
  d.check = check_mesh(d.mesh, &d.primal, false);
  d.stats = run_split(d.primal, p.dual, p.split, st, d.mesh, d.check, hooks);
  return d;
}

TEST(SplitDriver, SameMeshAsThePipelineWithoutOptimiser) {
  std::size_t split_meshes = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const TetSoup soup = random_classified_mesh(split_test_mesh_params(seed));
    PipelineParams p;
    p.optim.method = OptimParams::Method::None;
    p.tetopt.enabled = false;  // drive_split composes the stages without it
    const ConvertResult r = convert(soup, p);
    const Driven d = drive_split(soup, p, {});
    const std::string what = "seed " + std::to_string(seed);
    expect_same_mesh(d.mesh, r.mesh, what);
    EXPECT_EQ(d.check.invalid_cells, r.check.invalid_cells) << what;
    EXPECT_EQ(d.check.invalid_cells, 0u) << what;  // the closure's guarantee (proofs/split.md T1)
    const Json* kept = d.stats.find("kept_round");
    ASSERT_NE(kept, nullptr) << what;
    split_meshes += kept->dump(0) != "0";
  }
  EXPECT_GT(split_meshes, 0u);  // not vacuous: some meshes needed rounds
}

// A do-nothing optimiser (it keeps every valid cell valid, trivially): the
// rounds call it to untangle, the mesh kept once with the full method; the
// closure still ends every cell valid.
TEST(SplitDriver, OptimiserReachesTheLoopOnlyThroughItsCallback) {
  std::size_t untangles = 0, finals = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const TetSoup soup = random_classified_mesh(split_test_mesh_params(seed));
    std::size_t u = 0, f = 0;
    SplitHooks hooks;
    hooks.optimise = [&](PolyMesh& mesh, std::span<const char> seed_cells, std::span<const CellVerdict> verdicts,
                         bool untangle_only) {
      EXPECT_EQ(seed_cells.size(), mesh.num_cells());
      EXPECT_EQ(verdicts.size(), mesh.num_cells());
      ++(untangle_only ? u : f);
      return Json::object();
    };
    PipelineParams p;
    p.split.max_rounds = 2;
    const Driven d = drive_split(soup, p, hooks);
    const std::string what = "seed " + std::to_string(seed);
    EXPECT_EQ(d.check.invalid_cells, 0u) << what;
    const bool kept_split = d.stats.find("kept_round")->dump(0) != "0";
    EXPECT_EQ(f, kept_split ? 1u : 0u) << what;
    EXPECT_EQ(d.stats.find("optimize") != nullptr, kept_split) << what;
    untangles += u;
    finals += f;
  }
  EXPECT_GT(untangles, 0u);
  EXPECT_GT(finals, 0u);
}

// Without an optimiser the coarsening judges its trials locally (the cells
// of the vertices whose cuts changed, on the sub-mesh of their stars): the
// same cuts, mesh and verdicts as with every trial a whole build.
TEST(SplitDriver, LocalCoarseningTrialsMatchWholeBuilds) {
  std::size_t merged = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    RandomMeshParams mp = split_test_mesh_params(seed);
    // Large enough that the trials' stars are a small part of the mesh
    // (the sub-mesh path; below LocalTrials' share the whole mesh is used).
    mp.num_points = seed % 2 == 0 ? 600 : mp.num_points;
    const TetSoup soup = random_classified_mesh(mp);
    PipelineParams p;
    p.optim.method = OptimParams::Method::None;
    p.tetopt.enabled = false;
    p.split.coarsen = false;
    p.split.max_rounds = 1;  // the closure then cuts many vertices whole
    const Driven d = drive_split(soup, p, {});
    if (!d.st.cuts.any_whole()) continue;
    SplitState a = d.st, b = d.st;
    PolyMesh ma = d.mesh, mb = d.mesh;
    CheckResult ca = d.check, cb = d.check;
    const Json ja = coarsen_split(d.primal, p.dual, Metric::Q1, a, ma, ca, CoarsenStart::TopDown, true);
    const Json jb = coarsen_split(d.primal, p.dual, Metric::Q1, b, mb, cb, CoarsenStart::TopDown, false);
    const std::string what = "seed " + std::to_string(seed);
    EXPECT_EQ(ja.find("trials")->dump(0), "\"local\"") << what;
    EXPECT_TRUE(a.cuts.tri == b.cuts.tri) << what;
    expect_same_mesh(ma, mb, what);
    EXPECT_EQ(ca.invalid_cells, 0u) << what;
    ASSERT_EQ(ca.verdicts.size(), cb.verdicts.size()) << what;
    for (std::size_t c = 0; c < ca.verdicts.size(); ++c) EXPECT_EQ(ca.verdicts[c].valid, cb.verdicts[c].valid) << what;
    merged += ma.num_cells() < d.mesh.num_cells();
  }
  EXPECT_GT(merged, 0u);
}

// OpenFOAM's rounds (split_loop.cpp's foam_rounds): the cells of a vertex
// that the OpenFOAM hook names end as one corner per tet of its star (the
// vertex cut whole, or its coarsened classes split back: without an
// optimiser the closure leaves many vertices whole and coarsened) and every
// cell stays valid by the exact test, when the cut lowers the count of
// failing cells (a hook naming v's cells until they are its corners); a cut
// after which as many cells fail (a hook naming every cell of v, corners
// too) is undone and not tried again.
TEST(SplitDriver, CellsOpenFoamFailsAreCutIntoCorners) {
  std::size_t vertices_cut = 0, cuts_undone = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const TetSoup soup = random_classified_mesh(split_test_mesh_params(seed));
    const ClassifiedTetMesh primal = classify(soup, ClassifyParams{});
    VertexId v = VertexId::invalid();  // an interior vertex with the largest star
    for (std::size_t x = 0; x < primal.num_vertices(); ++x)
      if (primal.vertex_class(VertexId(x)).dim == 3 &&
          (!v.valid() || primal.vertex_tets(VertexId(x)).size() > primal.vertex_tets(v).size()))
        v = VertexId(x);
    ASSERT_TRUE(v.valid());
    const VertexId named(std::uint32_t(primal.input_vertex(v)));
    const std::size_t star = primal.vertex_tets(v).size();
    auto cells_of = [&](const PolyMesh& mesh) {
      std::vector<std::uint32_t> cells;
      for (std::uint32_t c = 0; c < mesh.num_cells(); ++c)
        if (mesh.cell_primal[c] == named) cells.push_back(c);
      return cells;
    };
    for (const bool corners_pass : {true, false}) {
      SplitHooks hooks;
      hooks.optimise = [](PolyMesh&, std::span<const char>, std::span<const CellVerdict>, bool) {
        return Json::object();
      };
      hooks.foam_failing = [&](const PolyMesh& mesh) {
        std::vector<std::uint32_t> cells = cells_of(mesh);
        if (corners_pass && cells.size() == star) cells.clear();
        return cells;
      };
      PipelineParams p;
      p.tetopt.enabled = false;
      const Driven d = drive_split(soup, p, hooks);
      const std::string what = "seed " + std::to_string(seed) + (corners_pass ? " corners pass" : " all fail");
      EXPECT_EQ(d.check.invalid_cells, 0u) << what;
      const Json* rounds = d.stats.find("foam_rounds");
      ASSERT_NE(rounds, nullptr) << what;
      const std::string text = rounds->dump(0);
      std::size_t records = 0;  // one "failing_cells" per round's record
      for (std::size_t at = text.find("\"failing_cells\""); at != std::string::npos;
           at = text.find("\"failing_cells\"", at + 1))
        ++records;
      const std::size_t cells_of_v = cells_of(d.mesh).size();
      if (corners_pass) {
        EXPECT_EQ(records, 1u) << what << text;  // the cut; then nothing fails
        EXPECT_TRUE(d.st.cuts.is_whole(v)) << what;
        EXPECT_EQ(cells_of_v, star) << what;
        vertices_cut += cells_of_v > 1;
      } else {
        EXPECT_LE(records, 2u) << what << text;  // at most the cut undone, then nothing to do
        if (text.find("\"undone\":true") == std::string::npos) continue;  // v was already corners
        EXPECT_LT(cells_of_v, star) << what;
        ++cuts_undone;
      }
    }
  }
  EXPECT_GT(vertices_cut, 0u);
  EXPECT_GT(cuts_undone, 0u);
}

}  // namespace
}  // namespace polydual
