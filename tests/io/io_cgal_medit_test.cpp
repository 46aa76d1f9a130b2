// CGAL Mesh_3 Medit output (CGAL::IO::output_to_medit) in both conventions,
// on the committed two-material ball of tests/data (written by
// tests/data/generators/mesh3_medit.cpp: subdomains 1 and 2 either side of a
// plane, 1404 tets, 695 boundary and interface triangles).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "classify/classify.h"
#include "core/error.h"
#include "io/medit_io.h"

namespace polydual {
namespace {

using testing::HasSubstr;

const std::string kData = POLYDUAL_TEST_DATA;

// Model face tag -> the regions on its sides, after classification.
std::map<std::int32_t, std::vector<std::int32_t>> face_regions(const TetSoup& s) {
  std::map<std::int32_t, std::vector<std::int32_t>> out;
  try {
    // At 180 degrees the feature angle does not split the (coarse, curved)
    // patches: the model faces are the reader's triangle tags.
    ClassifyParams whole;
    whole.feature_angle_deg = 180;
    const ClassifiedTetMesh m = classify(s, whole);
    EXPECT_EQ(m.num_tets(), 1404u);
    for (const ModelEntity& f : m.model().entities[2]) out[f.tag] = f.regions;
  } catch (const InputError& e) {
    ADD_FAILURE() << "classify rejected " << s.source << ": " << e.what();
  }
  return out;
}

TEST(IoCgalMedit, ShowPatchesFalseMergesTheTwoSidesByRegionPair) {
  const TetSoup s = read_medit_file(kData + "/cgal_twomat_sides.mesh");
  ASSERT_EQ(s.triangles.size(), 695u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_THAT(s.warnings[0], HasSubstr("cgal_twomat_sides.mesh: every triangle is written once per side"));
  EXPECT_THAT(s.warnings[0], HasSubstr("(1 = 1|outside, 2 = 1|2, 3 = 2|outside)"));
  ASSERT_EQ(s.groups.size(), 3u);
  EXPECT_EQ(s.groups[1].name, "subdomains 1|2");
  EXPECT_EQ(s.groups[1].tag, 2);
  // Each pair tag lies where its subdomains meet: the outer faces of 1 and 2
  // and the interface.
  const std::map<std::int32_t, std::vector<std::int32_t>> expected = {{1, {1}}, {2, {1, 2}}, {3, {2}}};
  EXPECT_EQ(face_regions(s), expected);
}

TEST(IoCgalMedit, ShowPatchesTrueKeepsThePatches) {
  const TetSoup s = read_medit_file(kData + "/cgal_twomat_patches.mesh");
  ASSERT_EQ(s.triangles.size(), 695u);
  EXPECT_TRUE(s.warnings.empty());
  std::map<std::int32_t, int> per_ref;
  for (const TaggedTriangle& t : s.triangles) ++per_ref[t.tag];
  EXPECT_EQ(per_ref, (std::map<std::int32_t, int>{{3, 249}, {4, 242}, {5, 204}}));
  // The patches are CGAL's surface patches, which near the junction curve
  // disagree with the cell labels: one triangle of the interface patch 5 lies
  // on the outer boundary of subdomain 1, one of patch 3 (subdomain 1's outer
  // boundary) on that of subdomain 2. The patches are kept as given, so those
  // two triangles become model faces of their own (fresh tags above the
  // largest patch, 5, numbered by their vertices, so 6 and 7 in some order).
  auto faces = face_regions(s);
  ASSERT_EQ(faces.size(), 5u);
  const std::set<std::vector<std::int32_t>> fresh = {faces[6], faces[7]};
  EXPECT_EQ(fresh, (std::set<std::vector<std::int32_t>>{{1}, {2}}));
  faces.erase(6);
  faces.erase(7);
  const std::map<std::int32_t, std::vector<std::int32_t>> expected = {{3, {1}}, {4, {2}}, {5, {1, 2}}};
  EXPECT_EQ(faces, expected);
}

TEST(IoCgalMedit, OneSidedDuplicatesAreNotMerged) {
  // A triangle written twice with the same orientation is not the CGAL
  // convention: both stay, and classify() reports the conflict.
  const std::string one_tet =
      "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
      "Triangles\n2\n1 2 3 1\n1 2 3 1\nTetrahedra\n1\n1 2 4 3 1\nEnd\n";
  const TetSoup s = read_medit(one_tet, "t.mesh");
  EXPECT_EQ(s.triangles.size(), 2u);
  EXPECT_TRUE(s.warnings.empty());
}

}  // namespace
}  // namespace polydual
