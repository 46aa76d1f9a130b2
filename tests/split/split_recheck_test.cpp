// The incremental star test of the split rounds (split/recheck.h,
// proofs/split.md L4): on random classified meshes, rounds that cut vertices
// whole and warm-start the rebuilt dual from the previous one, the verdicts
// that recheck_mesh carries over or recomputes equal, cell by cell, those of a
// full check_mesh of the rebuilt dual, and so do the exact-fallback counts.
#include "split/recheck.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "classify/classify.h"
#include "dual/build_dual.h"
#include "generate/random_mesh.h"
#include "split/cuts.h"
#include "split/warm_start.h"
#include "split_random_meshes.h"

namespace polydual {
namespace {

struct Tally {
  std::size_t rounds = 0, reused = 0, rechecked = 0, flipped = 0;
};

// The vertices of the invalid cells, and (round 1 only) every 5th vertex
// besides, so that whole cuts land all over the mesh.
void escalate(const ClassifiedTetMesh& m, const PolyMesh& mesh, const CheckResult& check, int round,
              std::vector<char>& whole) {
  const std::vector<VertexId> internal = internal_of_input(m);
  for (std::size_t c = 0; c < check.verdicts.size(); ++c)
    if (!check.verdicts[c].valid) whole[internal[mesh.cell_primal[c].idx].idx] = 1;
  if (round == 1)
    for (std::size_t v = 0; v < whole.size(); v += 5) whole[v] = 1;
}

void run_mesh(const TetSoup& soup, const std::string& what, Tally& tally) {
  const ClassifiedTetMesh m = classify(soup);
  const VertexCuts fe = free_edge_cuts(m);
  PolyMesh mesh = build_dual(m, {}, nullptr, &fe);
  CheckResult check = check_mesh(mesh, &m, false);
  std::vector<char> whole(m.num_vertices(), 0);
  for (int round = 1; round <= 3; ++round) {
    escalate(m, mesh, check, round, whole);
    std::vector<VertexId> ws;
    for (std::size_t v = 0; v < whole.size(); ++v)
      if (whole[v]) ws.push_back(VertexId(v));
    const VertexCuts cuts = VertexCuts::merged(m.num_vertices(), fe, fallback_cuts(m, ws));
    PolyMesh fresh = build_dual(m, {}, nullptr, &cuts);
    std::vector<PointId> from_old;
    warm_start(fresh, mesh, m, cuts, &from_old);
    // Round 2 also moves every third point a little (as an optimiser would):
    // cells whose points map one to one but sit elsewhere must be tested again.
    if (round == 2)
      for (std::size_t i = 0; i < fresh.num_points(); i += 3)
        fresh.points[i] = fresh.points[i] + 0.02 * Vec3{std::sin(double(i)), std::cos(double(i)), std::sin(2.0 * i)};
    RecheckStats st;
    const CheckResult inc = recheck_mesh(fresh, mesh, check, from_old, &st);
    const CheckResult full = check_mesh(fresh, &m, false);
    ASSERT_EQ(inc.verdicts.size(), full.verdicts.size()) << what;
    for (std::size_t c = 0; c < full.verdicts.size(); ++c) {
      ASSERT_EQ(inc.verdicts[c].valid, full.verdicts[c].valid) << what << " round " << round << " cell " << c;
      ASSERT_EQ(inc.verdicts[c].bad_tets, full.verdicts[c].bad_tets) << what << " round " << round << " cell " << c;
      ASSERT_EQ(inc.verdicts[c].total_tets, full.verdicts[c].total_tets) << what << " round " << round << " cell " << c;
    }
    EXPECT_EQ(inc.cell_exact, full.cell_exact) << what;
    EXPECT_EQ(inc.invalid_cells, full.invalid_cells) << what;
    EXPECT_EQ(inc.decomposition_tets, full.decomposition_tets) << what;
    EXPECT_EQ(inc.exact_fallbacks, full.exact_fallbacks) << what;
    EXPECT_EQ(st.reused + st.rechecked, fresh.num_cells());
    // Cells of vertices not cut whole whose verdict the round changed: a rule
    // that carried verdicts over by vertex would get these wrong.
    const std::vector<VertexId> internal = internal_of_input(m);
    for (std::size_t c = 0, d = 0; c < fresh.num_cells() && d < mesh.num_cells();) {
      const VertexId v = fresh.cell_primal[c];
      if (mesh.cell_primal[d] != v) break;
      std::size_t ec = c, ed = d;
      while (ec < fresh.num_cells() && fresh.cell_primal[ec] == v) ++ec;
      while (ed < mesh.num_cells() && mesh.cell_primal[ed] == v) ++ed;
      if (ec - c == ed - d && !whole[internal[v.idx].idx])
        for (std::size_t k = 0; k < ec - c; ++k) tally.flipped += full.verdicts[c + k].valid != check.verdicts[d + k].valid;
      c = ec;
      d = ed;
    }
    tally.rounds += 1;
    tally.reused += st.reused;
    tally.rechecked += st.rechecked;
    mesh = std::move(fresh);
    check = inc;
  }
}

TEST(SplitRecheck, RandomMeshesSameVerdictsAsFullCheck) {
  Tally tally;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    run_mesh(random_classified_mesh(split_test_mesh_params(seed)), "seed " + std::to_string(seed), tally);
    if (HasFailure()) break;
  }
  EXPECT_EQ(tally.rounds, 120u);
  // Both paths ran, and the rounds changed verdicts of cells whose own vertex
  // was not cut (what the recheck must not miss: a rule carrying verdicts
  // over by vertex, or one that compared only which points a cell has, fails).
  EXPECT_GT(tally.reused, 1000u);
  EXPECT_GT(tally.rechecked, 1000u);
  EXPECT_GT(tally.flipped, 20u);
  std::cout << "rounds " << tally.rounds << ": reused " << tally.reused << ", rechecked " << tally.rechecked
            << ", verdicts flipped at uncut vertices " << tally.flipped << "\n";
}

// same_cell itself: a cell equals itself through the identity map; one
// coordinate changed by one ulp, one point mapped elsewhere, or a missing
// partner makes it differ.
TEST(SplitRecheck, SameCellSeesEveryChange) {
  RandomMeshParams p;
  p.seed = 3;
  p.num_points = 50;
  const ClassifiedTetMesh m = classify(random_classified_mesh(p));
  const PolyMesh a = build_dual(m);
  std::vector<PointId> id(a.num_points());
  for (std::size_t i = 0; i < id.size(); ++i) id[i] = PointId(i);
  for (std::size_t c = 0; c < a.num_cells(); ++c) ASSERT_TRUE(same_cell(a, CellId(c), a, CellId(c), id));
  const CellId c(a.num_cells() / 2);
  const PointId p0 = a.face(a.cell(c)[0].face())[0];
  PolyMesh b = a;
  b.points[p0.idx].x = std::nextafter(b.points[p0.idx].x, 2.0);
  EXPECT_FALSE(same_cell(b, c, a, c, id));
  std::vector<PointId> swapped = id;
  const PointId p1 = a.face(a.cell(c)[0].face())[1];
  std::swap(swapped[p0.idx], swapped[p1.idx]);
  EXPECT_FALSE(same_cell(a, c, a, c, swapped));
  std::vector<PointId> missing = id;
  missing[p0.idx] = PointId::invalid();
  EXPECT_FALSE(same_cell(a, c, a, c, missing));
  EXPECT_FALSE(same_cell(a, c, a, CellId(c.idx + 1), id));
}

}  // namespace
}  // namespace polydual
