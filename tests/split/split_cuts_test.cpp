// The cut generators of the split stage (split/cuts.h), independently of the
// dual builder: v's star is joined across triangles on no model face and not
// in cut(v) (union-find); every model-face triangle at v must then have its
// two tets in different sides, and no cut triangle may have one side on both
// of its tets (no new slit).
#include "split/cuts.h"

#include <gtest/gtest.h>

#include "classify/classify.h"
#include "dual/build_dual.h"
#include "generate/domains.h"
#include "generate/random_mesh.h"
#include "pipeline/check.h"

namespace polydual {
namespace {

struct StarAudit {
  std::size_t slit = 0;      // model-face triangles with one side on both tets
  std::size_t new_slit = 0;  // cut triangles with one side on both tets
  std::size_t bad_cut = 0;   // cut triangles on a model face or not through v
};

StarAudit audit(const ClassifiedTetMesh& m, const VertexCuts& cuts) {
  StarAudit a;
  for (std::size_t vi = 0; vi < m.num_vertices(); ++vi) {
    const VertexId v(vi);
    const std::vector<std::uint32_t> side = star_sides(m, v, &cuts);
    const auto star = m.vertex_tets(v);
    for (std::size_t k = 0; k < star.size(); ++k)
      for (int i = 0; i < 4; ++i) {
        if (m.tet(star[k])[i] == v) continue;
        const TetId o = m.tet_neighbor(star[k], i);
        if (!o.valid()) continue;
        const TriId f = m.tet_triangle(star[k], i);
        const bool same = side[k] == side[m.star_rank(v, o)];
        if (m.on_model_face(f)) a.slit += same;
        else if (cuts.cuts(v, f)) a.new_slit += same;
      }
    for (TriId f : cuts.of(v)) {
      const auto t = m.triangle(f);
      a.bad_cut += m.on_model_face(f) || (t[0] != v && t[1] != v && t[2] != v);
    }
  }
  return a;
}

std::vector<VertexId> all_vertices(const ClassifiedTetMesh& m) {
  std::vector<VertexId> vs;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) vs.push_back(VertexId(v));
  return vs;
}

TEST(SplitCuts, FreeEdgeCutsSeparateEverySheetOnFracture) {
  const ClassifiedTetMesh m = classify(generate_domain(Domain::Fracture, 3000));
  const StarAudit before = audit(m, VertexCuts{});
  ASSERT_GT(before.slit, 0u);  // the fracture's tips are slit without cuts
  std::vector<VertexId> slit;
  const VertexCuts cuts = free_edge_cuts(m, &slit);
  EXPECT_FALSE(slit.empty());
  EXPECT_EQ(cuts.num_vertices_cut(), slit.size());
  const StarAudit a = audit(m, cuts);
  EXPECT_EQ(a.slit, 0u);
  EXPECT_EQ(a.new_slit, 0u);
  EXPECT_EQ(a.bad_cut, 0u);
}

TEST(SplitCuts, NoSlitNoCuts) {
  for (Domain d : {Domain::Cube, Domain::TwoMat, Domain::Fichera}) {
    const ClassifiedTetMesh m = classify(generate_domain(d, 1000));
    std::vector<VertexId> slit;
    EXPECT_TRUE(free_edge_cuts(m, &slit).empty()) << domain_name(d);
    EXPECT_TRUE(slit.empty());
  }
}

// Random fractures and crossing sheets: every generator keeps every sheet
// separated and makes no new slit.
TEST(SplitCuts, RandomMeshesAllGenerators) {
  for (std::uint64_t seed = 0; seed < 60; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 40 + int(seed % 5) * 20;
    p.fracture = true;
    p.crossing_sheet = seed % 2 == 1;
    p.regions = seed % 3 == 0 ? 2 : 1;
    const ClassifiedTetMesh m = classify(random_classified_mesh(p));
    const VertexCuts fe = free_edge_cuts(m);
    const std::vector<VertexId> vs = all_vertices(m);
    for (const VertexCuts& c :
         {fe, VertexCuts::merged(m.num_vertices(), fe, plane_cuts(m, vs)),
          VertexCuts::merged(m.num_vertices(), fe, fallback_cuts(m, vs))}) {
      const StarAudit a = audit(m, c);
      EXPECT_EQ(a.slit, 0u) << "seed " << seed;
      EXPECT_EQ(a.new_slit, 0u) << "seed " << seed;
      EXPECT_EQ(a.bad_cut, 0u) << "seed " << seed;
    }
  }
}

// Fallback: one side per tet of the star.
TEST(SplitCuts, FallbackGivesOneSidePerTet) {
  const ClassifiedTetMesh m = classify(generate_domain(Domain::Fichera, 800));
  const std::vector<VertexId> vs = all_vertices(m);
  const VertexCuts c = fallback_cuts(m, vs);
  for (VertexId v : vs) {
    const std::vector<std::uint32_t> side = star_sides(m, v, &c);
    EXPECT_EQ(*std::max_element(side.begin(), side.end()) + 1, side.size());
  }
}

// Plane cuts at Fichera's re-entrant edges cut the concave vertices' stars
// (more sides than without) and leave interior vertices alone.
TEST(SplitCuts, PlaneCutsAtConcaveEdges) {
  const ClassifiedTetMesh m = classify(generate_domain(Domain::Fichera, 2000));
  std::size_t more = 0, edge_vertices = 0;
  std::vector<VertexId> vs;
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (m.vertex_class(VertexId(v)).dim <= 1) vs.push_back(VertexId(v));
  const VertexCuts c = plane_cuts(m, vs);
  for (VertexId v : vs) {
    const auto a = star_sides(m, v, nullptr), b = star_sides(m, v, &c);
    ++edge_vertices;
    more += *std::max_element(b.begin(), b.end()) > *std::max_element(a.begin(), a.end());
  }
  EXPECT_GT(more, 0u);
  EXPECT_LT(more, edge_vertices);  // convex box edges: the planes do not cut the star
  const StarAudit a = audit(m, c);
  EXPECT_EQ(a.new_slit, 0u);
  EXPECT_EQ(a.bad_cut, 0u);
}

// With the free-edge cuts the dual builder makes no slit cell.
TEST(SplitCuts, DualWithFreeEdgeCutsHasNoSlitCell) {
  const ClassifiedTetMesh m = classify(generate_domain(Domain::Fracture, 3000));
  const VertexCuts cuts = free_edge_cuts(m);
  const PolyMesh plain = build_dual(m), cut = build_dual(m, {}, nullptr, &cuts);
  EXPECT_GT(check_mesh(plain, &m).validation.slit_cells, 0u);
  const CheckResult c = check_mesh(cut, &m);
  EXPECT_EQ(c.validation.slit_cells, 0u);
  EXPECT_TRUE(c.validation.ok());
}

}  // namespace
}  // namespace polydual
