// Edges whose tets fall into several chains (proofs/edge_chains.md E1-E3):
// where a mesh touches itself along an edge, with the outside between its
// parts on both sides, as where three materials and the outside meet in a
// CGAL Mesh_3 mesh of a labelled image. Every fan of every chain has its
// face, so every cell of the dual is closed, before and after the split.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>

#include "classify/classify.h"
#include "core/error.h"
#include "dual/build_dual.h"
#include "io/medit_io.h"
#include "mesh/validate.h"
#include "pipeline/convert.h"

namespace polydual {
namespace {

const std::string kData = POLYDUAL_TEST_DATA;

// The smallest configuration: two tets sharing only the edge (0,0,0)-(1,0,0)
// (input vertices 0 and 1), one above the plane z = 0 and one below, the
// outside between them on both sides of the edge; regions r1 and r2.
TetSoup two_tets_sharing_an_edge(std::int32_t r1, std::int32_t r2) {
  TetSoup s;
  s.source = "two tets sharing an edge";
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, -1}};
  s.tets = {{0, 1, 2, 3}, {0, 1, 4, 5}};
  s.tet_region = {r1, r2};
  return s;
}

// The tets around one such edge of a CGAL Mesh_3 mesh of the blocks image
// (experiments/meshgen/labelled_image_medit shape=blocks n=64
// facet_size=0.04 cell_size=0.04, where materials 2 and 3 touch along the
// line x = y = 0.5): two tets of material 2 joined across a triangle, one of
// material 3, the outside on both sides between them. The shared edge joins
// input vertices 3 and 5.
TetSoup cgal_junction() {
  TetSoup s;
  s.source = "cgal junction";
  s.points = {{0.46420612152434282, 0.49218783542343958, 0.65047018079394536},
              {0.52124829159090857, 0.49218800449889333, 0.68849538850414638},
              {0.46995337046072172, 0.49218732424885014, 0.69443534352446867},
              {0.49218805237180896, 0.5062763791935484, 0.66917069798988305},
              {0.49243967829816127, 0.49908172893771424, 0.70951371585012768},
              {0.4921871448226236, 0.48403830534457071, 0.69088650049895395},
              {0.49218776907902212, 0.46144579381147333, 0.67286925450527524}};
  s.tets = {{5, 3, 4, 1}, {5, 0, 2, 3}, {3, 5, 0, 6}};
  s.tet_region = {3, 2, 2};
  return s;
}

// The faces of pm between a cell of input vertex a and a cell of input
// vertex b (the fan faces of the edge (a, b)).
std::size_t faces_between(const PolyMesh& pm, std::uint32_t a, std::uint32_t b) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < pm.num_faces(); ++f) {
    if (!pm.face_neighbour[f].valid()) continue;
    const std::uint32_t p = pm.cell_primal[pm.face_owner[f].idx].idx, q = pm.cell_primal[pm.face_neighbour[f].idx].idx;
    n += (p == a && q == b) || (p == b && q == a);
  }
  return n;
}

// Closed, manifold (every cell edge in exactly two half-faces) and sound.
void expect_closed(const PolyMesh& pm, const ClassifiedTetMesh& m, const std::string& what) {
  const ValidationReport r = validate(pm, &m);
  EXPECT_EQ(r.closed_cells, r.cells) << what;
  EXPECT_EQ(r.manifold_cells, r.cells) << what;
  EXPECT_EQ(r.face_errors, 0u) << what;
  EXPECT_TRUE(r.missing_model_entities.empty()) << what;
}

TEST(DualChains, TwoTetsSharingOnlyAnEdge) {
  for (const auto& [r1, r2] : {std::pair{1, 1}, std::pair{2, 3}}) {
    const std::string what = "regions " + std::to_string(r1) + ", " + std::to_string(r2);
    const ClassifiedTetMesh m = classify(two_tets_sharing_an_edge(r1, r2));
    ASSERT_EQ(m.multi_chain_edges().size(), 1u) << what;
    const auto ends = m.edge(m.multi_chain_edges()[0]);
    EXPECT_EQ((std::set<std::uint32_t>{m.input_vertex(ends[0]), m.input_vertex(ends[1])}),
              (std::set<std::uint32_t>{0, 1}))
        << what;
    const PolyMesh pm = build_dual(m);
    // Each end of the edge has one cell per tet (two sides), the other
    // vertices one each; each chain's fan is a face between its two cells.
    EXPECT_EQ(pm.num_cells(), 8u) << what;
    EXPECT_EQ(faces_between(pm, 0, 1), 2u) << what;
    expect_closed(pm, m, what);
    // Planar model faces: the dual covers each material (L5; up to the
    // rounding of the centres of the slanted faces, which are not
    // axis-aligned). Without the second chain's fan a tet's corner was lost.
    const ValidationReport r = validate(pm, &m);
    ASSERT_EQ(r.material_volume.size(), r.primal_material_volume.size()) << what;
    for (const auto& [tag, v] : r.primal_material_volume)
      EXPECT_NEAR(r.material_volume.at(tag), v, 1e-14) << what << ", material " << tag;
  }
}

TEST(DualChains, ThreeTetsAroundACgalJunctionEdge) {
  const ClassifiedTetMesh m = classify(cgal_junction());
  ASSERT_EQ(m.multi_chain_edges().size(), 1u);
  const PolyMesh pm = build_dual(m);
  // Vertices 3 and 5: a side for the chain of two tets of material 2 and one
  // for the tet of material 3.
  EXPECT_EQ(faces_between(pm, 3, 5), 2u);
  expect_closed(pm, m, "cgal junction");
  // The same with the cleanup off.
  DualParams raw;
  raw.cleanup = false;
  expect_closed(build_dual(m, raw), m, "cgal junction, no cleanup");
}

// A closed ring of four tets round the axis (0,0,-1)-(0,0,1) and a fifth tet
// on the axis inside the ring's first wedge: each triangle has at most two
// tets, on its two sides, but the tets overlap round the axis, where the dual
// could not close the cells (proofs/edge_chains.md E1 (ii)). Refused.
TEST(DualChains, OverlapRoundAnEdgeIsRefused) {
  TetSoup s;
  s.source = "ring and one more";
  s.points = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0.5, 0.1, 0}, {0.1, 0.5, 0}};
  s.tets = {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 5}, {0, 1, 5, 2}, {0, 1, 6, 7}};
  s.tet_region = {1, 1, 1, 1, 1};
  // The input check refuses it first (classify/self_overlap.h: the fifth
  // tet's boundary triangles cross the ring's); build_dual's count of the
  // tets its ring walks visit is the second guard, for a classified mesh
  // that did not come through classify().
  try {
    (void)classify(s);
    ADD_FAILURE() << "an overlap round an edge must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ring and one more"), std::string::npos) << e.what();
  }
  // Without the fifth tet: the ring alone is a valid mesh.
  s.tets.pop_back();
  s.tet_region.pop_back();
  EXPECT_NO_THROW(build_dual(classify(s)));
}

// The blocks image at a coarse size (experiments/meshgen/labelled_image_medit
// shape=blocks n=32 facet_size=0.15 cell_size=0.15 facet_distance=0.02;
// CGAL's output_to_medit, every triangle once per side): 1829 tets with
// several edges where materials 2 and 3 touch between two wedges of outside.
// Before every chain had its faces, the raw dual had 6 open cells and the
// split one 10.
TEST(DualChains, CgalLabelledImageConvertsWithEveryCellClosed) {
  const TetSoup soup = read_medit_file(kData + "/cgal_threemat_blocks_sides.mesh");
  ASSERT_EQ(soup.tets.size(), 1829u);
  std::size_t raw_cells = 0;
  for (double angle : {30.0, 180.0}) {
    PipelineParams raw;
    raw.classify.feature_angle_deg = angle;
    raw.split.enabled = false;
    raw.optim.method = OptimParams::Method::None;
    raw.tetopt.enabled = false;  // the same primal as the split's below
    const ConvertResult r = convert(soup, raw);
    EXPECT_GE(r.primal.multi_chain_edges().size(), 3u) << "the mesh must still touch itself along edges";
    EXPECT_EQ(r.check.validation.closed_cells, r.check.validation.cells) << "raw, feature angle " << angle;
    EXPECT_EQ(r.check.validation.manifold_cells, r.check.validation.cells) << "raw, feature angle " << angle;
    EXPECT_EQ(r.check.validation.face_errors, 0u);
    EXPECT_GT(r.check.invalid_cells, 0u) << "the split below must have work";
    raw_cells = r.mesh.num_cells();
  }
  // Optimised, then the cells still invalid split (without the tet
  // optimisation, which leaves none to split on this mesh).
  PipelineParams split_p;
  split_p.tetopt.enabled = false;
  const ConvertResult r = convert(soup, split_p);
  EXPECT_GT(r.mesh.num_cells(), raw_cells) << "cells were split";
  EXPECT_EQ(r.report.invalid_after, 0u);
  EXPECT_EQ(r.check.validation.closed_cells, r.check.validation.cells) << "after the split";
  EXPECT_EQ(r.check.validation.manifold_cells, r.check.validation.cells) << "after the split";
  EXPECT_EQ(r.check.validation.face_errors, 0u);
  EXPECT_TRUE(r.check.validation.missing_model_entities.empty());
}

}  // namespace
}  // namespace polydual
