// The split's local rounds (split/local_round.h, proofs/split.md L5): on
// random classified meshes with free-edge cuts and vertices cut whole, the
// sub-mesh carries the whole mesh's classification (mesh/sub_mesh.h), every
// cell of a vertex of N[D] not cut whole in the sub-mesh's dual is, half-face by half-face
// and coordinate by coordinate, the same cell of the whole mesh's dual, and
// local_round's invalid counts are those of the whole mesh's exact check.
#include "split/local_round.h"

#include <gtest/gtest.h>

#include <bit>

#include "classify/classify.h"
#include "core/error.h"
#include "dual/build_dual.h"
#include "generate/random_mesh.h"
#include "pipeline/check.h"
#include "split/cuts.h"
#include "split_random_meshes.h"

namespace polydual {
namespace {

bool same_bits(const Point3& a, const Point3& b) {
  return std::bit_cast<std::uint64_t>(a.x) == std::bit_cast<std::uint64_t>(b.x) &&
         std::bit_cast<std::uint64_t>(a.y) == std::bit_cast<std::uint64_t>(b.y) &&
         std::bit_cast<std::uint64_t>(a.z) == std::bit_cast<std::uint64_t>(b.z);
}

// Cells by input vertex: [first, end) per vertex (cells are grouped by vertex).
std::vector<std::pair<std::size_t, std::size_t>> cells_by_vertex(const PolyMesh& pm, std::size_t num_input) {
  std::vector<std::pair<std::size_t, std::size_t>> out(num_input, {0, 0});
  for (std::size_t c = 0; c < pm.num_cells();) {
    std::size_t e = c;
    while (e < pm.num_cells() && pm.cell_primal[e] == pm.cell_primal[c]) ++e;
    out[pm.cell_primal[c].idx] = {c, e};
    c = e;
  }
  return out;
}

// Whether cell c of a and cell d of b have the same half-faces, in order, each
// with the same oriented loop of bitwise equal coordinates.
bool same_geometry(const PolyMesh& a, CellId c, const PolyMesh& b, CellId d) {
  const auto hc = a.cell(c), hd = b.cell(d);
  if (hc.size() != hd.size()) return false;
  for (std::size_t h = 0; h < hc.size(); ++h) {
    const auto fa = a.face(hc[h].face()), fb = b.face(hd[h].face());
    if (fa.size() != fb.size() || hc[h].side() != hd[h].side()) return false;
    for (std::size_t i = 0; i < fa.size(); ++i)
      if (!same_bits(a.points[fa[i].idx], b.points[fb[i].idx])) return false;
  }
  return true;
}

TEST(SubMesh, CarriesTheClassification) {
  for (std::uint64_t seed = 0; seed < 12; ++seed) {
    const ClassifiedTetMesh m = classify(random_classified_mesh(split_test_mesh_params(seed)));
    std::vector<VertexId> some;
    for (std::size_t v = 0; v < m.num_vertices(); v += 4) some.push_back(VertexId(v));
    const std::vector<TetId> tets = star_tets(m, some);
    ASSERT_TRUE(std::is_sorted(tets.begin(), tets.end(), [](TetId a, TetId b) { return a.idx < b.idx; }));
    const SubMesh s = sub_mesh(m, tets);
    ASSERT_EQ(s.mesh.num_tets(), tets.size());
    for (std::size_t t = 0; t < tets.size(); ++t) {
      const TetId st(t), wt = tets[t];
      EXPECT_EQ(s.mesh.region(st), m.region(wt));
      EXPECT_EQ(s.mesh.input_tet(st), m.input_tet(wt));
      for (int i = 0; i < 4; ++i) {
        const VertexId sv = s.mesh.tet(st)[i];
        EXPECT_EQ(s.vertex[sv.idx], m.tet(wt)[i]);
        EXPECT_EQ(s.mesh.vertex_class(sv), m.vertex_class(m.tet(wt)[i]));
        EXPECT_EQ(s.mesh.on_model_face(s.mesh.tet_triangle(st, i)), m.on_model_face(m.tet_triangle(wt, i)));
        if (m.on_model_face(m.tet_triangle(wt, i)))
          EXPECT_EQ(s.mesh.triangle_class(s.mesh.tet_triangle(st, i)), m.triangle_class(m.tet_triangle(wt, i)));
      }
      for (int k = 0; k < 6; ++k) {
        const EdgeId se = s.mesh.tet_edge(st, k), we = m.tet_edge(wt, k);
        EXPECT_EQ(s.mesh.edge_class(se), m.edge_class(we));
        // Edges at a listed vertex have all their tets here: the same stored
        // tet and orientation as in the whole mesh.
        const auto [a, b] = m.edge(we);
        if (std::find(some.begin(), some.end(), a) == some.end() && std::find(some.begin(), some.end(), b) == some.end())
          continue;
        EXPECT_EQ(s.vertex[s.mesh.edge(se)[0].idx], a);
        EXPECT_EQ(s.vertex[s.mesh.edge(se)[1].idx], b);
        EXPECT_EQ(s.tet[s.mesh.edge_tet(se).idx], m.edge_tet(we));
      }
    }
    EXPECT_THROW(sub_mesh(m, std::vector<TetId>{TetId(1), TetId(0)}), std::invalid_argument);
  }
}

TEST(LocalRound, CellsAndVerdictsAreThoseOfTheWholeDual) {
  std::size_t compared = 0, invalid_seen = 0, changed_verdicts = 0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const std::string what = "seed " + std::to_string(seed);
    const ClassifiedTetMesh m = classify(random_classified_mesh(split_test_mesh_params(seed)));
    const DualParams dp;
    const VertexCuts fe = free_edge_cuts(m);
    const PolyMesh first = build_dual(m, dp, nullptr, &fe);
    const CheckResult first_check = check_mesh(first, &m, false);
    // D: the vertices of the first dual's invalid cells, and every 9th
    // vertex besides (whole cuts all over the mesh, next to uncut vertices).
    std::vector<char> whole(m.num_vertices(), 0);
    std::vector<VertexId> internal(m.num_vertices());
    for (std::size_t v = 0; v < m.num_vertices(); ++v) internal[m.input_vertex(VertexId(v))] = VertexId(v);
    for (std::size_t c = 0; c < first.num_cells(); ++c)
      if (!first_check.verdicts[c].valid) whole[internal[first.cell_primal[c].idx].idx] = 1;
    for (std::size_t v = seed % 9; v < whole.size(); v += 9) whole[v] = 1;
    std::vector<VertexId> d;
    for (std::size_t v = 0; v < whole.size(); ++v)
      if (whole[v]) d.push_back(VertexId(v));
    const VertexCuts cuts = VertexCuts::merged(m.num_vertices(), fe, fallback_cuts(m, d));
    const PolyMesh full = build_dual(m, dp, nullptr, &cuts);
    const CheckResult full_check = check_mesh(full, &m, false);
    const double collapse = dual_collapse_length(m, dp);

    const auto in_full = cells_by_vertex(full, m.num_vertices());
    // Both ways of building: on a sub-mesh (share 1: never the whole mesh)
    // and on the whole mesh, scoped (share 0).
    for (double share : {1.0, 0.0}) {
      const LocalDual ld = local_dual(m, fe, whole, d, dp, collapse, share);
      // U: the vertices not cut whole next to one that is (none when every
      // vertex is whole: nothing to build).
      bool any_u = false;
      for (std::size_t t = 0; t < m.num_tets() && !any_u; ++t) {
        bool has_whole = false, has_other = false;
        for (VertexId w : m.tet(TetId(t))) (whole[w.idx] ? has_whole : has_other) = true;
        any_u = has_whole && has_other;
      }
      ASSERT_EQ(ld.on_whole_mesh, share == 0.0 && any_u) << what;
      ASSERT_EQ(std::count(ld.active.begin(), ld.active.end(), char(1)) > 0, any_u) << what;
      const auto in_local = cells_by_vertex(ld.dual, m.num_vertices());
      for (std::size_t v = 0; v < ld.active.size(); ++v) {
        if (!ld.active[v]) continue;
        const std::uint32_t in = m.input_vertex(ld.whole_vertex(v));
        const auto [fc, fe_] = in_full[in];
        const auto [lc, le] = in_local[in];
        ASSERT_EQ(fe_ - fc, le - lc) << what << " vertex " << in;
        for (std::size_t k = 0; k < fe_ - fc; ++k) {
          ASSERT_TRUE(same_geometry(full, CellId(fc + k), ld.dual, CellId(lc + k))) << what << " vertex " << in;
          ++compared;
        }
      }
    }

    if (seed == 0) {  // a scope must flag every vertex of the mesh it is given
      const std::vector<char> short_flags(m.num_vertices() - 1, 1);
      const DualScope bad{short_flags, collapse};
      EXPECT_THROW(build_dual(m, dp, nullptr, &cuts, &bad), UsageError);
    }

    const LocalRound lr = local_round(m, fe, whole, d, dp, collapse, seed % 2 ? 1.0 : 0.0);
    ASSERT_EQ(lr.vertices.size(), lr.invalid.size());
    for (std::size_t i = 0; i < lr.vertices.size(); ++i) {
      const std::uint32_t in = m.input_vertex(lr.vertices[i]);
      std::uint32_t bad = 0, bad_before = 0;
      for (std::size_t c = in_full[in].first; c < in_full[in].second; ++c) bad += !full_check.verdicts[c].valid;
      for (std::size_t c = 0; c < first.num_cells(); ++c)
        bad_before += first.cell_primal[c].idx == in && !first_check.verdicts[c].valid;
      EXPECT_EQ(lr.invalid[i], bad) << what << " vertex " << in;
      invalid_seen += bad;
      changed_verdicts += (bad > 0) != (bad_before > 0);
    }
    // The round tests no vertex cut whole (barycentric corners), and every
    // other vertex with an invalid cell is in U = N[D] minus those.
    std::vector<char> in_u(m.num_vertices(), 0);
    for (VertexId v : lr.vertices) {
      EXPECT_FALSE(whole[v.idx]) << what << " vertex " << m.input_vertex(v);
      in_u[v.idx] = 1;
    }
    for (std::size_t c = 0; c < full.num_cells(); ++c) {
      const VertexId v = internal[full.cell_primal[c].idx];
      if (!full_check.verdicts[c].valid && !whole[v.idx]) EXPECT_TRUE(in_u[v.idx]) << what;
    }
    if (HasFailure()) break;
  }
  // The comparison ran on many cells, some of them invalid, and the cuts
  // changed verdicts (a local round that returned the old verdicts fails).
  EXPECT_GT(compared, 2500u);  // cells of vertices not cut whole
  EXPECT_GT(invalid_seen, 0u);
  EXPECT_GT(changed_verdicts, 10u);
  std::cout << "cells compared " << compared << ", invalid " << invalid_seen << ", vertices whose validity changed "
            << changed_verdicts << "\n";
}

}  // namespace
}  // namespace polydual
