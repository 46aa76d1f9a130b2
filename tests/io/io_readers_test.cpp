// Each reader on the committed 5-tet cube (tests/data, layout in
// make_binary.py): four corner tets of region 10 around a centre tet of region
// 20, cube faces tagged 1..6, the centre tet's faces tagged 7.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "classify/classify.h"
#include "core/error.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"
#include "io/read_tet_mesh.h"
#include "io/tetgen_io.h"
#include "io/vtu_reader.h"

namespace polydual {
namespace {

const std::string kData = POLYDUAL_TEST_DATA;

const std::vector<std::array<std::uint32_t, 4>> kTets = {
    {0, 1, 2, 4}, {3, 1, 7, 2}, {5, 1, 4, 7}, {6, 2, 7, 4}, {1, 2, 4, 7}};
const std::vector<std::int32_t> kRegions = {10, 10, 10, 10, 20};

// Points are the unit cube corners numbered v = x + 2y + 4z.
void expect_cube(const TetSoup& s) {
  ASSERT_EQ(s.points.size(), 8u);
  for (std::uint32_t v = 0; v < 8; ++v) {
    EXPECT_EQ(s.points[v].x, double(v & 1)) << v;
    EXPECT_EQ(s.points[v].y, double((v >> 1) & 1)) << v;
    EXPECT_EQ(s.points[v].z, double((v >> 2) & 1)) << v;
  }
  EXPECT_EQ(s.tets, kTets);
  EXPECT_EQ(s.tet_region, kRegions);
}

// The 12 boundary triangles carry their cube face (1..6), the 4 interface
// triangles tag 7: count per tag.
void expect_face_tags(const TetSoup& s) {
  ASSERT_EQ(s.triangles.size(), 16u);
  std::array<int, 8> per_tag{};
  for (const TaggedTriangle& t : s.triangles) {
    ASSERT_GE(t.tag, 1);
    ASSERT_LE(t.tag, 7);
    ++per_tag[t.tag];
  }
  for (int tag = 1; tag <= 6; ++tag) EXPECT_EQ(per_tag[tag], 2) << tag;
  EXPECT_EQ(per_tag[7], 4);
}

void expect_classifies(const TetSoup& s) {
  try {
    classify(s);
  } catch (const InputError& e) {
    ADD_FAILURE() << "classify rejected " << s.source << ": " << e.what();
  }
}

TEST(IoReaders, Msh41AsciiFullClassification) {
  const TetSoup s = read_msh_file(kData + "/cube5.msh");
  expect_cube(s);
  expect_face_tags(s);
  EXPECT_TRUE(s.full_classification);
  EXPECT_EQ(s.edges.size(), 18u);   // 12 cube edges + 6 face diagonals
  EXPECT_EQ(s.corners.size(), 8u);  // the quad block is ignored
  EXPECT_EQ(s.corners[7].v, 7u);
  EXPECT_EQ(s.corners[7].tag, 8);
  EXPECT_EQ(s.source, kData + "/cube5.msh");
  expect_classifies(s);
}

TEST(IoReaders, Msh41BinaryEqualsAscii) {
  const TetSoup a = read_msh_file(kData + "/cube5.msh");
  const TetSoup b = read_msh_file(kData + "/cube5_bin.msh");
  expect_cube(b);
  expect_face_tags(b);
  EXPECT_TRUE(b.full_classification);
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    EXPECT_EQ(a.triangles[i].v, b.triangles[i].v);
    EXPECT_EQ(a.triangles[i].tag, b.triangles[i].tag);
  }
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i) EXPECT_EQ(a.edges[i].tag, b.edges[i].tag);
  EXPECT_EQ(a.corners.size(), b.corners.size());
}

TEST(IoReaders, Msh22AsciiPhysicalElseElementary) {
  const TetSoup s = read_msh_file(kData + "/cube5_v2.msh");
  expect_cube(s);
  expect_face_tags(s);  // physical 0 -> elementary tag
  EXPECT_FALSE(s.full_classification);
  ASSERT_EQ(s.corners.size(), 1u);
  EXPECT_EQ(s.corners[0].v, 0u);
  EXPECT_EQ(s.corners[0].tag, 5);
  expect_classifies(s);
}

// Node tags far apart, above the header's maximum and beyond 32 bits (the
// readers keep small tags in an array, the others in a hash map): the nodes
// are still found in file order, and a tag given twice is still an error,
// whichever side of the array's end it is on.
std::string msh41_one_tet(const std::array<std::string, 4>& tags, const std::string& element_nodes) {
  std::string f = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 3 5\n3 1 0 4\n";
  for (const std::string& t : tags) f += t + "\n";
  f += "0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 " + element_nodes +
       "\n$EndElements\n";
  return f;
}

// The tag array grows with the nodes read: tag 5000, first of 1302 nodes, is
// kept in the map; tag 5001, last, grows the array past 5000, whose slot
// stays empty: 5000 must still be found (and a second 5000 refused).
TEST(IoReaders, MshNodeTagKeptInTheMapBeforeTheArrayGrewPastIt) {
  auto file = [](const std::string& last) {
    std::string f = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1302\n5000 0 0 1\n";
    for (int i = 1; i <= 1300; ++i) f += std::to_string(i) + " " + std::to_string(i) + " 0 0\n";
    return f + last + " 0 1 0\n$EndNodes\n$Elements\n1\n1 4 2 1 1 5000 1 2 5001\n$EndElements\n";
  };
  const TetSoup s = read_msh(file("5001"), "t.msh");
  ASSERT_EQ(s.tets.size(), 1u);
  EXPECT_EQ(s.tets[0], (std::array<std::uint32_t, 4>{0, 1, 2, 1301}));
  try {
    read_msh(file("5000"), "t.msh");
    ADD_FAILURE() << "no error for a repeated tag";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("line 1307: node 5000 defined twice"));
  }
}

TEST(IoReaders, MshSparseAndHugeNodeTags) {
  const TetSoup s = read_msh(msh41_one_tet({"7", "1000000000", "3", "1099511627776"}, "1000000000 3 1099511627776 7"), "t.msh");
  ASSERT_EQ(s.tets.size(), 1u);
  EXPECT_EQ(s.tets[0], (std::array<std::uint32_t, 4>{1, 2, 3, 0}));
  EXPECT_EQ(s.points[1].x, 1.0);
  EXPECT_EQ(s.points[3].z, 1.0);
  const TetSoup t = read_msh(
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n5000000000 0 0 0\n2 1 0 0\n-4 0 1 0\n9 0 0 1\n$EndNodes\n"
      "$Elements\n1\n1 4 2 1 1 9 -4 2 5000000000\n$EndElements\n",
      "t.msh");
  ASSERT_EQ(t.tets.size(), 1u);
  EXPECT_EQ(t.tets[0], (std::array<std::uint32_t, 4>{3, 2, 1, 0}));
  auto error = [](const std::string& bytes) {
    try {
      read_msh(bytes, "t.msh");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // The header's maximum tag is 5: 3 and 5 are held in the array, 7 and up in the map.
  EXPECT_THAT(error(msh41_one_tet({"3", "1000000000", "7", "3"}, "7 3 1000000000 3")),
              testing::HasSubstr("node tag 3 defined twice"));
  EXPECT_THAT(error(msh41_one_tet({"7", "1000000000", "3", "7"}, "7 3 1000000000 7")),
              testing::HasSubstr("node tag 7 defined twice"));
  EXPECT_THAT(error(msh41_one_tet({"7", "1099511627776", "3", "1099511627776"}, "7 3 1099511627776 7")),
              testing::HasSubstr("node tag 1099511627776 defined twice"));
  EXPECT_THAT(error(msh41_one_tet({"7", "1000000000", "3", "4"}, "7 3 1000000000 5")),
              testing::HasSubstr("element 1: node 5 is not defined in $Nodes"));
  EXPECT_THAT(error(msh41_one_tet({"7", "1000000000", "3", "4"}, "7 3 1000000000 99999999999")),
              testing::HasSubstr("element 1: node 99999999999 is not defined in $Nodes"));
}

TEST(IoReaders, Msh22Binary) {
  const TetSoup s = read_msh_file(kData + "/cube5_v2_bin.msh");
  expect_cube(s);
  expect_face_tags(s);
  EXPECT_FALSE(s.full_classification);
  expect_classifies(s);
}

TEST(IoReaders, Medit) {
  const TetSoup s = read_medit_file(kData + "/cube5.mesh");
  expect_cube(s);
  expect_face_tags(s);
  EXPECT_EQ(s.edges.size(), 18u);
  ASSERT_EQ(s.corners.size(), 8u);
  EXPECT_EQ(s.corners[2].v, 2u);
  EXPECT_EQ(s.corners[2].tag, 3);  // Medit corners: tag = 1-based index
  EXPECT_FALSE(s.full_classification);
  expect_classifies(s);
}

TEST(IoReaders, TetGenByNodeOrEleZeroBased) {
  for (const char* name : {"/cube5.node", "/cube5.ele", "/cube5"}) {
    const TetSoup s = read_tetgen_files(kData + name);
    expect_cube(s);
    expect_face_tags(s);
  }
  expect_classifies(read_tetgen_files(kData + "/cube5.ele"));
}

TEST(IoReaders, TetGenOneBasedWithoutFaceOrAttributes) {
  const TetSoup s = read_tetgen("4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 0\n1 1 2 3 4\n",
                                std::nullopt, "mem");
  ASSERT_EQ(s.tets.size(), 1u);
  EXPECT_EQ(s.tets[0], (std::array<std::uint32_t, 4>{0, 1, 2, 3}));
  EXPECT_EQ(s.tet_region, std::vector<std::int32_t>{1});
  EXPECT_TRUE(s.triangles.empty());
}

TEST(IoReaders, VtuAsciiWithTrianglesAndRegionArray) {
  const TetSoup s = read_vtu_file(kData + "/cube5.vtu");
  expect_cube(s);
  expect_face_tags(s);
  expect_classifies(s);
}

TEST(IoReaders, VtuBinaryBothHeaderLayouts) {
  for (const char* name : {"/cube5_bin.vtu", "/cube5_bin32.vtu"}) {
    const TetSoup s = read_vtu_file(kData + name);
    expect_cube(s);
    EXPECT_TRUE(s.triangles.empty());
  }
}

TEST(IoReaders, VtuWithoutRegionArrayGivesRegionOne) {
  const std::string vtu =
      R"(<VTKFile type="UnstructuredGrid"><UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="1">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>
<Cells><DataArray type="Int32" Name="connectivity">0 1 2 3</DataArray>
<DataArray type="Int32" Name="offsets">0 4</DataArray><DataArray type="Int32" Name="types">10</DataArray></Cells>
</Piece></UnstructuredGrid></VTKFile>)";
  const TetSoup s = read_vtu(vtu, "mem.vtu");
  ASSERT_EQ(s.tets.size(), 1u);  // offsets with a leading 0 (VTK 9) accepted
  EXPECT_EQ(s.tet_region, std::vector<std::int32_t>{1});
}

TEST(IoReaders, DispatchByExtension) {
  EXPECT_EQ(read_tet_mesh(kData + "/cube5.msh").tets.size(), 5u);
  EXPECT_EQ(read_tet_mesh(kData + "/cube5.mesh").tets.size(), 5u);
  EXPECT_EQ(read_tet_mesh(kData + "/cube5.node").tets.size(), 5u);
  EXPECT_EQ(read_tet_mesh(kData + "/cube5.vtu").tets.size(), 5u);
  try {
    read_tet_mesh(kData + "/no_such_file.msh");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("no_such_file.msh: cannot open file"));
  }
  try {
    read_tet_mesh(kData + "/make_binary.py");
    ADD_FAILURE() << "no error for an unknown extension";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("unknown mesh file extension '.py'"));
  }
}

}  // namespace
}  // namespace polydual
