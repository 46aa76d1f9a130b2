// The reference a mixed dual is validated against (quality/primal_reference.h):
// every model entity of a PrimalMesh must be represented in its dual and each
// material with planar model faces keeps its volume; validate() finds a
// dual from which a model vertex, edge or face, or some volume, is taken.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "classify/classify_primal.h"
#include "dual/primal_dual.h"
#include "generate/random_mixed.h"
#include "mesh/cell_soup.h"
#include "quality/check_result.h"
#include "quality/primal_reference.h"

namespace polydual {
namespace {

struct Block {
  PrimalMesh primal;
  PrimalReference ref;
  PolyMesh dual;
};

// A jittered hexahedral block joined to tets through pyramids, n cubes a side.
Block block(std::uint64_t seed, int n = 2) {
  Block b;
  b.primal = build_primal(cell_soup(random_hex_pyramid_tets(seed, n, 0.3)));
  b.ref = primal_reference(b.primal);
  b.dual = build_primal_dual(b.primal, DualParams{});
  return b;
}

bool lists(const ValidationReport& r, const std::string& item) {
  return std::find(r.missing_model_entities.begin(), r.missing_model_entities.end(), item) !=
         r.missing_model_entities.end();
}

TEST(PrimalReference, TheDualOfAMixedBlockRepresentsTheModelAndKeepsItsVolumes) {
  for (std::uint64_t s = 0; s < 4; ++s) {
    const Block b = block(s, s % 2 == 0 ? 2 : 4);
    // The unit box's 8 corners, 12 edges and 6 faces, and the interface z =
    // 1/2: 4 more corners where it meets the box's vertical edges, 4 more
    // edges round it, one more face.
    EXPECT_EQ(b.ref.entities[0].size(), 12u) << s;
    EXPECT_EQ(b.ref.entities[1].size(), 16u) << s;
    EXPECT_EQ(b.ref.entities[2].size(), 7u) << s;
    EXPECT_TRUE(b.ref.curved_regions.empty()) << s;
    EXPECT_NEAR(b.ref.material_volume.at(1), 0.5, 1e-12) << s;
    EXPECT_NEAR(b.ref.material_volume.at(2), 0.5, 1e-12) << s;
    const ValidationReport r = check_mesh(b.dual, b.ref).validation;
    EXPECT_TRUE(r.missing_model_entities.empty()) << s;
    EXPECT_EQ(r.volume_checked_materials, (std::vector<std::int32_t>{1, 2})) << s;
    EXPECT_TRUE(r.ok() && r.geometry_ok()) << s;
  }
}

TEST(PrimalReference, AModelVertexEdgeOrFaceTakenFromTheDualIsMissing) {
  const Block b = block(1);
  const std::int32_t vertex = b.ref.entities[0].front(), edge = b.ref.entities[1].back();
  const std::int32_t face = b.ref.entities[2].front(), other = b.ref.entities[2].back();
  PolyMesh pm = b.dual;
  for (std::size_t p = 0; p < pm.num_points(); ++p) {
    ModelRef& c = pm.point_class[p];
    if ((c.dim == 0 && c.tag == vertex) || (c.dim == 1 && c.tag == edge)) c = ModelRef{3, 1};
  }
  for (std::int32_t& t : pm.face_tag)
    if (t == face) t = other;
  const ValidationReport r = validate(pm, b.ref);
  EXPECT_TRUE(lists(r, "model vertex " + std::to_string(vertex)));
  EXPECT_TRUE(lists(r, "model edge " + std::to_string(edge)));
  EXPECT_TRUE(lists(r, "model face " + std::to_string(face)));
  EXPECT_FALSE(r.ok());
  // Without the reference nothing of the model is checked.
  EXPECT_TRUE(validate(pm).missing_model_entities.empty());
}

TEST(PrimalReference, AMaterialThatLosesVolumeIsAMismatch) {
  const Block b = block(2);
  PolyMesh pm = b.dual;
  // Every dual point on the bottom face z = 0 (region 1's) moves inwards.
  std::size_t moved = 0;
  for (std::size_t p = 0; p < pm.num_points(); ++p)
    if (pm.point_class[p].dim == 2 && pm.points[p].z == 0.0) pm.points[p].z = 0.05, ++moved;
  ASSERT_GT(moved, 0u);
  const ValidationReport r = validate(pm, b.ref);
  ASSERT_EQ(r.volume_mismatches.size(), 1u);
  EXPECT_EQ(r.volume_mismatches[0].material, 1);
  EXPECT_LT(r.volume_mismatches[0].dual, r.volume_mismatches[0].primal);
}

TEST(PrimalReference, AMaterialBoundedByACurvedModelFaceIsNotCompared) {
  TetSoup soup = random_hex_pyramid_tets(3, 4, 0.3);
  // A point inside the box's bottom face z = 0 (region 1's only) moves
  // outwards: that face is no longer planar, so region 1 (z < 1/2) is not
  // compared; region 2 still is.
  std::size_t moved = 0;
  for (Point3& x : soup.points)
    if (x.z == 0.0 && x.x > 0 && x.x < 1 && x.y > 0 && x.y < 1 && moved == 0) x.z = -0.05, ++moved;
  ASSERT_EQ(moved, 1u);
  const PrimalMesh m = build_primal(cell_soup(soup));
  const PrimalReference ref = primal_reference(m);
  EXPECT_EQ(ref.curved_regions, (std::set<std::int32_t>{1}));
  const ValidationReport r = validate(build_primal_dual(m, DualParams{}), ref);
  EXPECT_EQ(r.volume_checked_materials, (std::vector<std::int32_t>{2}));
}

}  // namespace
}  // namespace polydual
