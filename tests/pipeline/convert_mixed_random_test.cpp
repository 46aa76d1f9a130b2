// Property tests of the mixed pipeline (design §14, proofs/mixed_dual.md) on
// random mixed meshes (generate/random_mixed.h): prism layers grown on the
// boundary of random classified tet meshes (materials, fractures, fins,
// networks, lattice points), and jittered hexahedral blocks joined to tets
// through pyramids. For each: the raw dual (caps and keep) has closed cells,
// sound faces and the box's volume (its model faces are planar); the default
// convert() keeps them so, its split leaves no invalid cell but at a vertex it
// cut whole (each such cell is reported, --require-valid refuses the mesh);
// outputs do not depend on the thread count.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cmath>
#include <map>
#include <string>

#include "classify/classify_primal.h"
#include "dual/primal_dual.h"
#include "generate/random_mixed.h"
#include "mesh/cell_soup.h"
#include "mesh/validate.h"
#include "optim/optimize.h"
#include "mesh/model_facets.h"
#include "core/error.h"
#include "pipeline/convert.h"
#include "quality/check_result.h"
#include "split/mixed_split.h"

namespace polydual {
namespace {

struct Case {
  std::string name;
  TetSoup soup;
  double volume;                           // of the whole box
  std::map<std::int32_t, double> regions;  // exact material volumes, where known
};

// Seed s: a random tet family (as the tet property tests vary it) under 1 to
// 3 prism layers of first height 0.02 to 0.05 and ratio 1.2 to 1.5.
Case prism_case(std::uint64_t s) {
  RandomMeshParams p;
  p.seed = s;
  p.num_points = 40 + int(s % 3) * 30;
  p.face_points = 4 + int(s % 3) * 3;
  p.regions = s % 2 == 0 ? 2 : 1;
  p.fracture = s % 3 == 1;
  p.crossing_sheet = s % 6 == 1;
  p.network = s % 7 == 3;
  p.fins = s % 4 == 2;
  p.lattice_points = s % 5 == 4;
  const int layers = 1 + int(s % 3);
  const double first = 0.02 + 0.01 * double(s % 4), ratio = 1.2 + 0.1 * double(s % 4);
  double h = 0;
  for (int k = 0; k < layers; ++k) h += first * std::pow(ratio, k);
  return {"prism layers seed " + std::to_string(s), random_prism_layers(p, layers, first, ratio),
          std::pow(1 + 2 * h, 3), {}};
}

// Seed s: n = 2 or 4 cubes a side, jitter 0.1 to 0.4 of a cube; the
// hexahedra (region 1) fill z < 1/2 exactly, the interface is planar.
Case hex_case(std::uint64_t s) {
  const int n = s % 2 == 0 ? 4 : 2;
  const double jitter = 0.1 + 0.1 * double(s % 4);
  return {"hex block seed " + std::to_string(s), random_hex_pyramid_tets(s, n, jitter), 1.0, {{1, 0.5}, {2, 0.5}}};
}

std::vector<Case> cases() {
  std::vector<Case> all;
  for (std::uint64_t s = 0; s < 6; ++s) all.push_back(prism_case(s));
  for (std::uint64_t s = 0; s < 8; ++s) all.push_back(hex_case(s));
  return all;
}

void expect_volumes(const PolyMesh& pm, const Case& c, const std::string& what) {
  double sum = 0;
  std::map<std::int32_t, double> by_region;
  for (std::size_t k = 0; k < pm.num_cells(); ++k) {
    const double v = cell_volume(pm, CellId(k));
    sum += v;
    by_region[pm.cell_material[k]] += v;
  }
  EXPECT_NEAR(sum, c.volume, 1e-12 * c.volume) << what;
  for (const auto& [region, volume] : c.regions) EXPECT_NEAR(by_region[region], volume, 1e-12) << what << " region " << region;
}

TEST(ConvertMixedRandom, RawDualIsClosedAndKeepsTheVolume) {
  for (const Case& c : cases()) {
    const PrimalMesh m = build_primal(cell_soup(c.soup));
    for (BoundaryMode mode : {BoundaryMode::Caps, BoundaryMode::Keep}) {
      DualParams dp;
      dp.boundary = mode;
      const PolyMesh pm = build_primal_dual(m, dp);
      const std::string what = c.name + " " + boundary_mode_name(mode);
      const CheckResult check = check_mesh(pm, nullptr);
      EXPECT_EQ(check.validation.closed_cells, pm.num_cells()) << what;
      EXPECT_EQ(check.validation.face_errors, 0u) << what;
      expect_volumes(pm, c, what);
    }
  }
}

// The number of dual cells of each primal vertex (input numbering).
std::map<std::uint32_t, std::size_t> cells_per_vertex(const PolyMesh& pm) {
  std::map<std::uint32_t, std::size_t> n;
  for (const VertexId v : pm.cell_primal) ++n[v.idx];
  return n;
}

// The mixed split (design §14): every cell stays closed and the volume exact;
// a cell still invalid is a corner of a vertex cut whole (one dual cell per
// primal cell round it: the split did all it can there); every invalid cell
// is listed, and --require-valid refuses exactly the meshes that have one.
TEST(ConvertMixedRandom, DefaultConvertSplitsUntilOnlyCutCornersMayStayInvalid) {
  std::size_t before = 0, after = 0;
  for (const Case& c : cases()) {
    const ConvertResult r = convert(c.soup, PipelineParams{});
    ASSERT_TRUE(r.mixed.has_value()) << c.name;
    EXPECT_TRUE(r.check.validation.defects().empty()) << c.name;
    EXPECT_EQ(r.check.validation.closed_cells, r.mesh.num_cells()) << c.name;
    expect_volumes(r.mesh, c, c.name + " optimised");
    EXPECT_EQ(invalid_cells_defect(r).count, r.check.invalid_cells) << c.name;
    const PrimalMesh& m = r.mixed->mesh;
    std::map<std::uint64_t, VertexId> vertex;
    for (std::size_t v = 0; v < m.num_vertices(); ++v) vertex[m.input_vertex(VertexId(v))] = VertexId(std::uint32_t(v));
    const auto per_vertex = cells_per_vertex(r.mesh);
    for (std::size_t k = 0; k < r.mesh.num_cells(); ++k) {
      if (r.check.verdicts[k].valid) continue;
      const std::uint32_t in = r.mesh.cell_primal[k].idx;
      EXPECT_EQ(per_vertex.at(in), m.vertex_cells(vertex.at(in)).size()) << c.name << ": cell " << k << " is not a cut corner";
    }
    if (c.name.rfind("hex", 0) == 0 && r.check.invalid_cells == 0) {  // small: a second conversion is cheap
      PipelineParams strict;
      strict.split.require_valid = true;
      EXPECT_NO_THROW(convert(c.soup, strict)) << c.name;
    }
    before += r.report.invalid_before;
    after += r.report.invalid_after;
  }
  // The raw duals of these meshes are far from star-shaped (random Delaunay
  // tets, jittered blocks); the optimiser and the split leave almost nothing.
  EXPECT_GT(before, 100u);
  EXPECT_LE(after * 100, before);
}

// --no-split: the optimiser alone, which never adds an invalid cell, and
// --require-valid refuses what it leaves, naming the cells.
TEST(ConvertMixedRandom, WithoutTheSplitTheOptimiserNeverAddsAnInvalidCell) {
  PipelineParams params;
  params.split.enabled = false;
  for (const Case& c : {prism_case(0), hex_case(4)}) {
    const ConvertResult r = convert(c.soup, params);
    EXPECT_EQ(r.report.stage("split"), nullptr) << c.name;
    EXPECT_LE(r.report.invalid_after, r.report.invalid_before) << c.name;
    EXPECT_GT(r.report.invalid_after, 0u) << c.name << ": the split's work is needed on these";
    PipelineParams strict = params;
    strict.split.require_valid = true;
    try {
      convert(c.soup, strict);
      ADD_FAILURE() << c.name << ": no InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cells remain invalid"), std::string::npos) << e.what();
    }
  }
}

TEST(ConvertMixedRandom, SameOutputForAnyThreadCount) {
  for (const Case& c : {prism_case(3), hex_case(5)}) {
    const ConvertResult all = convert(c.soup, PipelineParams{});
    tbb::task_arena one(1);
    const ConvertResult single = one.execute([&] { return convert(c.soup, PipelineParams{}); });
    EXPECT_EQ(all.mesh.points, single.mesh.points) << c.name;
    EXPECT_EQ(all.mesh.face_points, single.mesh.face_points) << c.name;
    EXPECT_EQ(all.mesh.face_owner, single.mesh.face_owner) << c.name;
    EXPECT_EQ(all.mesh.cell_offsets, single.mesh.cell_offsets) << c.name;
  }
}

// The mixed split's OpenFOAM rounds (split/mixed_split.h), from the default
// convert()'s valid mesh with the pipeline's optimiser: the primal vertex
// whose cells the OpenFOAM hook names is cut whole, one corner per primal
// cell round it, unless that round would leave a cell invalid (then it is
// undone); no cell is invalid after; a hook that goes on naming corners
// already cut stops the rounds.
TEST(ConvertMixedRandom, CellsOpenFoamFailsAreCutIntoCorners) {
  std::size_t cut = 0;
  for (std::uint64_t s = 0; s < 4; ++s) {
    const Case c = hex_case(s);
    const ConvertResult r = convert(c.soup, PipelineParams{});
    ASSERT_EQ(r.check.invalid_cells, 0u) << c.name;
    const PrimalMesh& m = r.mixed->mesh;
    VertexId v = VertexId::invalid();  // an interior vertex with the most cells round it
    for (std::size_t x = 0; x < m.num_vertices(); ++x)
      if (m.vertex_class(VertexId(x)).dim == 3 &&
          (!v.valid() || m.vertex_cells(VertexId(x)).size() > m.vertex_cells(v).size()))
        v = VertexId(x);
    ASSERT_TRUE(v.valid()) << c.name;
    const VertexId named(std::uint32_t(m.input_vertex(v)));
    auto cells_of_v = [&](const PolyMesh& pm) {
      std::size_t n = 0;
      for (VertexId x : pm.cell_primal) n += x == named;
      return n;
    };
    const ModelFacets facets = model_facets(m);
    OptimParams optim;
    optim.method = OptimParams::Method::Untangle;
    SplitHooks hooks;
    hooks.optimise = [&](PolyMesh& pm, std::span<const char> seed, std::span<const CellVerdict> verdicts, bool) {
      return optimize(pm, &facets, optim, {}, seed, verdicts).to_json();
    };
    std::size_t calls = 0;
    hooks.foam_failing = [&](const PolyMesh& pm) {
      ++calls;
      std::vector<std::uint32_t> cells;
      for (std::uint32_t k = 0; k < pm.num_cells(); ++k)
        if (pm.cell_primal[k] == named) cells.push_back(k);
      return cells;
    };
    PolyMesh mesh = r.mesh;
    CheckResult check = check_mesh(mesh, nullptr, false);
    const std::size_t before = cells_of_v(mesh);
    const MixedSplitRun run = run_mixed_split(m, PipelineParams{}.dual, SplitParams{}, mesh, check, hooks);
    EXPECT_EQ(check.invalid_cells, 0u) << c.name;
    const std::size_t after = cells_of_v(mesh);
    const bool whole = after == m.vertex_cells(v).size();
    EXPECT_TRUE(whole || (after == before && run.rounds == 0)) << c.name << ": " << before << " -> " << after;
    EXPECT_EQ(calls, whole ? 2u : 1u) << c.name;  // after the cut the hook names corners only
    cut += whole && before < after;
  }
  EXPECT_GT(cut, 0u);
}

}  // namespace
}  // namespace polydual
