// Lower-dimensional input not attached to the tets (io/unattached.h): dropped
// and counted, while attached but wrong input stays an error of classify().
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "classify/classify.h"
#include "core/error.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"

namespace polydual {
namespace {

using testing::HasSubstr;

// One tet on nodes 1..4; node 5 is a construction point, node 6 a free node.
const std::string kHead =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
    "$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 5 5 5\n6 6 6 6\n$EndNodes\n";

TEST(IoUnattached, MshDropsWhatNoTetUses) {
  const TetSoup s = read_msh(kHead +
                                 "$Elements\n8\n"
                                 "1 15 2 0 1 5\n"        // point entity 1 on the construction point
                                 "2 15 2 0 2 1\n"        // point entity 2 on a tet vertex: kept
                                 "3 1 2 0 7 1 1\n"       // curve 7 collapsed to a point
                                 "4 1 2 0 8 5 6\n"       // curve 8 bounding no volume
                                 "5 1 2 0 9 1 2\n"       // curve 9 on the tet: kept
                                 "6 2 2 0 3 1 2 6\n"     // surface 3: one triangle outside...
                                 "7 2 2 0 3 1 3 2\n"     // ...one on the tet: surface 3 kept
                                 "8 4 2 1 1 1 2 3 4\n"
                                 "$EndElements\n",
                             "t.msh");
  EXPECT_EQ(s.ignored.points, 1u);
  EXPECT_EQ(s.ignored.curves, 2u);
  EXPECT_EQ(s.ignored.surfaces, 0u);
  EXPECT_EQ(s.ignored.elements, 4u);
  ASSERT_EQ(s.corners.size(), 1u);
  EXPECT_EQ(s.corners[0].tag, 2);
  ASSERT_EQ(s.edges.size(), 1u);
  EXPECT_EQ(s.edges[0].tag, 9);
  ASSERT_EQ(s.triangles.size(), 1u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0],
            "t.msh: ignored 4 lower-dimensional elements not attached to the tets (3 with a vertex no tet uses, "
            "1 degenerate with a repeated vertex); model entities with no element on the tets: 1 point, 2 curves, "
            "0 surfaces");
  EXPECT_NO_THROW(classify(s));
}

TEST(IoUnattached, AttachedTriangleThatIsNoFaceStaysAnError) {
  // Nodes 1..5 are all tet vertices; triangle (1, 4, 5) is no face of a tet.
  const TetSoup s = read_msh(
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
      "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 0 0 -1\n$EndNodes\n"
      "$Elements\n3\n1 2 2 0 3 1 4 5\n2 4 2 1 1 1 2 3 4\n3 4 2 1 1 1 3 2 5\n$EndElements\n",
      "t.msh");
  EXPECT_EQ(s.triangles.size(), 1u);
  EXPECT_FALSE(s.ignored.any());
  try {
    classify(s);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("triangle 1: triangle (1, 4, 5) is not a face of any tet"));
  }
}

TEST(IoUnattached, MeditDegenerateEdgeAndUnusedCorner) {
  const TetSoup s = read_medit(
      "MeshVersionFormatted 2\nDimension 3\nVertices\n5\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n9 9 9 0\n"
      "Tetrahedra\n1\n1 2 3 4 1\nEdges\n2\n1 1 4\n1 2 5\nCorners\n2\n5\n1\nEnd\n",
      "t.mesh");
  EXPECT_EQ(s.ignored.elements, 2u);
  EXPECT_EQ(s.ignored.curves, 1u);  // edge ref 4 (degenerate) is gone, ref 5 kept
  EXPECT_EQ(s.ignored.points, 1u);  // Medit corners are their own entities
  EXPECT_EQ(s.edges.size(), 1u);
  EXPECT_EQ(s.corners.size(), 1u);
  EXPECT_NO_THROW(classify(s));
}

TEST(IoUnattached, Msh4PhysicalNamesAndSecondOrderTet) {
  // A 10-node tet of volume 1 in physical group 5 "solid part".
  const TetSoup s = read_msh(
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 5 \"solid part\"\n$EndPhysicalNames\n"
      "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 1 5 0\n$EndEntities\n"
      "$Nodes\n1 10 1 10\n3 1 0 10\n1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n.5 0 0\n.5 .5 0\n0 .5 0\n0 0 .5\n0 .5 .5\n.5 0 .5\n$EndNodes\n"
      "$Elements\n1 1 1 1\n3 1 11 1\n1 1 2 3 4 5 6 7 8 9 10\n$EndElements\n",
      "t.msh");
  ASSERT_EQ(s.tets.size(), 1u);
  EXPECT_EQ(s.tets[0], (std::array<std::uint32_t, 4>{0, 1, 2, 3}));
  EXPECT_EQ(s.tet_region[0], 5);
  ASSERT_EQ(s.groups.size(), 1u);
  EXPECT_EQ(s.groups[0].name, "solid part");
  EXPECT_EQ(s.groups[0].dim, 3);
  EXPECT_EQ(s.groups[0].entities, std::vector<std::int32_t>{5});
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], "t.msh: second-order elements: using their corner vertices (the other nodes are left unused)");
  EXPECT_EQ(classify(s).num_vertices(), 4u);
}

// Gmsh declares an OpenCASCADE sphere's poles as degenerate curves with no
// element: nothing is dropped, so the warning names the empty entities only
// (not "ignored 0 lower-dimensional elements").
TEST(IoUnattached, DeclaredEntitiesWithNoElementAreNamedAsSuch) {
  const TetSoup s = read_msh_file(std::string(POLYDUAL_TEST_DATA) + "/gmsh/sphere_coarse.msh");
  EXPECT_EQ(s.ignored.elements, 0u);
  EXPECT_EQ(s.ignored.curves, 2u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].find("ignored"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("2 curves, 0 surfaces (declared by the file with no element)"), std::string::npos)
      << s.warnings[0];
}

}  // namespace
}  // namespace polydual

