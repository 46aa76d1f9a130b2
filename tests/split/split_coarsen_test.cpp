// Coarsening of whole cuts (split/coarsen.h, proofs/split.md L6): the
// barycentric corners of each whole vertex are merged back while every cell
// stays valid. Checked: every result valid and sound, never more cells than
// without it and fewer over a family; without optimisation (every point of
// a whole vertex at its barycentre) each vertex's cells fill exactly the
// volume they filled before, vertex by vertex (a merged cell is the union of
// its corners, and the neighbours' cells are unchanged: the whole vertex's
// triangles keep their centres, dual/cut_topology.h kCentre); the top-down
// start (CoarsenStart::TopDown) refines only what its evaluator fails and
// keeps fewer cells than the corners' start; outputs are the same for one
// and two threads.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include <tbb/global_control.h>

#include "dual/build_dual.h"
#include "generate/random_mesh.h"
#include "mesh/validate.h"
#include "pipeline/convert.h"
#include "quality/check_result.h"
#include "split/coarsen.h"
#include "split/cuts.h"

namespace polydual {
namespace {

RandomMeshParams coarsen_mesh(int i) {
  RandomMeshParams mp;
  mp.seed = std::uint64_t(7000 + i);
  mp.num_points = 24 + (i % 6) * 10;
  mp.notch = i % 2 == 0;
  mp.lattice_points = i % 3 == 0;
  mp.fracture = i % 4 == 1;
  mp.regions = i % 5 == 2 ? 2 : 1;
  return mp;
}

ConvertResult run(const TetSoup& soup, OptimParams::Method method, bool coarsen) {
  PipelineParams p;
  p.optim.method = method;
  p.split.max_rounds = 1;  // the closure then cuts many vertices whole
  p.split.coarsen = coarsen;
  return convert(soup, p);
}

// Per primal vertex (input numbering), the summed volume of its cells.
std::map<std::uint32_t, double> vertex_volumes(const PolyMesh& pm) {
  std::map<std::uint32_t, double> v;
  for (std::size_t c = 0; c < pm.num_cells(); ++c) v[pm.cell_primal[c].idx] += cell_volume(pm, CellId(c));
  return v;
}

TEST(SplitCoarsen, RandomMeshesStayValidWithFewerCells) {
  std::size_t fine = 0, coarse = 0, merged_unoptimised = 0;
  for (int i = 0; i < 30; ++i) {
    const TetSoup soup = random_classified_mesh(coarsen_mesh(i));
    const auto method = i % 5 == 0 ? OptimParams::Method::Local : OptimParams::Method::None;
    const ConvertResult off = run(soup, method, false);
    const ConvertResult on = run(soup, method, true);
    ASSERT_EQ(on.check.invalid_cells, 0u) << "mesh " << i;
    EXPECT_TRUE(on.check.validation.ok()) << "mesh " << i;
    EXPECT_LE(on.mesh.num_cells(), off.mesh.num_cells()) << "mesh " << i;
    fine += off.mesh.num_cells();
    coarse += on.mesh.num_cells();
    if (method != OptimParams::Method::None) continue;
    merged_unoptimised += on.mesh.num_cells() < off.mesh.num_cells();
    // Points at their barycentres in both: the same volume per vertex.
    const auto a = vertex_volumes(off.mesh), b = vertex_volumes(on.mesh);
    ASSERT_EQ(a.size(), b.size()) << "mesh " << i;
    for (const auto& [v, vol] : a)
      EXPECT_NEAR(b.at(v), vol, 1e-12 * (1 + std::abs(vol))) << "mesh " << i << " vertex " << v;
  }
  // Not vacuous: corners were merged, also where the volumes were compared.
  EXPECT_LT(coarse, fine);
  EXPECT_GT(merged_unoptimised, 0u);
}

// Whole vertices for the start tests: every third vertex of m.
std::vector<char> every_third(const ClassifiedTetMesh& m) {
  std::vector<char> whole(m.num_vertices(), 0);
  for (std::size_t v = 0; v < whole.size(); v += 3) whole[v] = 1;
  return whole;
}

// The sides of whole vertices in `cuts` that hold more than one tet.
std::vector<BadCell> merged_sides(const ClassifiedTetMesh& m, std::span<const char> whole, const VertexCuts& cuts) {
  std::vector<BadCell> out;
  for (std::size_t v = 0; v < whole.size(); ++v) {
    if (!whole[v]) continue;
    const std::vector<std::uint32_t> side = star_sides(m, VertexId(v), &cuts);
    std::map<std::uint32_t, int> n;
    for (std::uint32_t s : side) ++n[s];
    for (const auto& [s, count] : n)
      if (count > 1) out.push_back({VertexId(v), s});
  }
  return out;
}

// The top-down start only refines what fails: an evaluator that fails every
// merged cell gets the corners back (the valid start), one that fails
// nothing keeps every whole vertex one cell per side (no label cut).
TEST(SplitCoarsen, TopDownStartRefinesOnlyWhatFails) {
  for (int i = 0; i < 6; ++i) {
    const ConvertResult r = run(random_classified_mesh(coarsen_mesh(i)), OptimParams::Method::None, false);
    const ClassifiedTetMesh& m = r.primal;
    const VertexCuts free = free_edge_cuts(m);
    const std::vector<char> whole = every_third(m);
    const VertexCuts corners = with_whole_cuts(m, free, whole);
    std::size_t evaluations = 0;
    const VertexCuts refused = coarsen_whole_cuts(
        m, free, whole,
        [&](const VertexCuts& c) {
          ++evaluations;
          return merged_sides(m, whole, c);
        },
        nullptr, kCoarsenMaxPasses, CoarsenStart::TopDown);
    EXPECT_TRUE(refused.tri == corners.tri) << "mesh " << i;
    EXPECT_GT(evaluations, 1u) << "mesh " << i;
    const VertexCuts accepted = coarsen_whole_cuts(
        m, free, whole, [](const VertexCuts&) { return std::vector<BadCell>{}; }, nullptr, kCoarsenMaxPasses,
        CoarsenStart::TopDown);
    VertexCuts expected = free;
    expected.whole = whole;
    EXPECT_TRUE(accepted.tri == expected.tri) << "mesh " << i;
    EXPECT_TRUE(merged_sides(m, whole, accepted).size() > 0) << "mesh " << i;
  }
}

// Without an optimiser the coarsening starts top-down: fewer cells than from
// the corners on this family (the merged cells are judged where the pinned
// points put them, exactly, in both).
TEST(SplitCoarsen, TopDownStartKeepsFewerCellsThanCorners) {
  std::size_t top_down = 0, corners = 0;
  for (int i = 0; i < 12; ++i) {
    const ConvertResult r = run(random_classified_mesh(coarsen_mesh(i)), OptimParams::Method::None, false);
    const ClassifiedTetMesh& m = r.primal;
    const VertexCuts free = free_edge_cuts(m);
    const std::vector<char> whole = every_third(m);
    const DualParams dual;
    auto evaluate = [&](const VertexCuts& c) {
      const PolyMesh pm = build_dual(m, dual, nullptr, &c);
      const CheckResult check = check_mesh(pm, &m, false);
      const std::vector<VertexId> internal = internal_of_input(m);
      std::vector<BadCell> bad;
      std::uint32_t rank = 0;
      for (std::size_t k = 0; k < pm.num_cells(); ++k) {
        rank = k > 0 && pm.cell_primal[k] == pm.cell_primal[k - 1] ? rank + 1 : 0;
        const VertexId v = internal[pm.cell_primal[k].idx];
        // The whole vertices' cells only: the corners are valid (the
        // coarsening's precondition), the other cells need not be.
        if (whole[v.idx] && !check.verdicts[k].valid) bad.push_back({v, rank});
      }
      return bad;
    };
    for (const CoarsenStart start : {CoarsenStart::Corners, CoarsenStart::TopDown}) {
      const VertexCuts c = coarsen_whole_cuts(m, free, whole, evaluate, nullptr, kCoarsenMaxPasses, start);
      ASSERT_TRUE(evaluate(c).empty()) << "mesh " << i;
      (start == CoarsenStart::TopDown ? top_down : corners) += build_dual(m, dual, nullptr, &c).num_cells();
    }
  }
  EXPECT_LT(top_down, corners);
}

TEST(SplitCoarsen, SameOutputForAnyThreadCount) {
  for (int i = 1; i < 6; ++i) {
    const TetSoup soup = random_classified_mesh(coarsen_mesh(i));
    // Both starts: the optimiser's (from the corners) and top-down.
    const auto method = i % 2 == 0 ? OptimParams::Method::None : OptimParams::Method::Local;
    ConvertResult one, two;
    {
      tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
      one = run(soup, method, true);
    }
    {
      tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
      two = run(soup, method, true);
    }
    ASSERT_EQ(one.mesh.num_cells(), two.mesh.num_cells()) << "mesh " << i;
    ASSERT_EQ(one.mesh.points.size(), two.mesh.points.size()) << "mesh " << i;
    for (std::size_t p = 0; p < one.mesh.points.size(); ++p)
      ASSERT_TRUE(one.mesh.points[p] == two.mesh.points[p]) << "mesh " << i << " point " << p;
    EXPECT_EQ(one.mesh.face_points, two.mesh.face_points) << "mesh " << i;
  }
}

}  // namespace
}  // namespace polydual
