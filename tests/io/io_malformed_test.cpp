// A catalogue of malformed inputs: each must fail with an InputError that
// names the problem and the place (line, byte or element), never crash or be
// read as a silently wrong mesh. Geometric faults (inverted, zero-volume,
// duplicated, non-conformal tets) are found by classify() after reading.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>

#include "classify/classify.h"
#include "core/error.h"
#include "io/file_bytes.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"
#include "io/tetgen_io.h"
#include "io/vtu_reader.h"

namespace polydual {
namespace {

using testing::AllOf;
using testing::HasSubstr;
using io::read_file_bytes;

const std::string kData = POLYDUAL_TEST_DATA;

// The message of the InputError `f` throws, or a marker when it throws none.
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("wrong exception type: ") + e.what();
  }
  return "no error";
}
std::string msh(const std::string& text) { return error_of([&] { read_msh(text, "t.msh"); }); }
std::string medit(const std::string& text) { return error_of([&] { read_medit(text, "t.mesh"); }); }
std::string vtu(const std::string& text) { return error_of([&] { read_vtu(text, "t.vtu"); }); }
std::string tetgen(const std::string& node, const std::string& ele, const std::string& face = "") {
  return error_of([&] {
    read_tetgen(node, ele, face.empty() ? std::nullopt : std::optional<std::string_view>(face), "t");
  });
}
std::string medit_then_classify(const std::string& text) {
  return error_of([&] { classify(read_medit(text, "t.mesh")); });
}

const std::string kMsh2Head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
const std::string kMsh2Nodes = "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n";  // lines 4-10
const std::string kMsh4Head = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
const std::string kMeditHead = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n";
const std::string kNode = "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n";
const std::string kVtuHeadForNul = "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid>\n";

// ---- Gmsh
TEST(IoMalformed, GarbageHeader) {
  EXPECT_THAT(msh("solid cube\nfacet normal 0 0 1\n"), HasSubstr("t.msh: line 1: not a Gmsh file: expected $MeshFormat"));
  EXPECT_THAT(msh(""), HasSubstr("t.msh: the file is empty"));
  EXPECT_THAT(msh(" \n\n"), HasSubstr("t.msh: the file is empty"));
}

TEST(IoMalformed, UnsupportedMshVersion) {
  EXPECT_THAT(msh("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n"), HasSubstr("line 2: msh format version '3.0' not supported"));
}

TEST(IoMalformed, TruncatedAsciiFile) {
  const std::string whole = read_file_bytes(kData + "/cube5.msh");
  const std::string cut = whole.substr(0, whole.find("$EndNodes") - 8);
  EXPECT_THAT(msh(cut), AllOf(HasSubstr("line 58: "), HasSubstr("file too short for 4 node records")));
  const std::string mid_line = whole.substr(0, whole.find("$EndNodes") - 3);
  EXPECT_THAT(msh(mid_line), HasSubstr("line 66: file ends while reading coordinate"));
}

TEST(IoMalformed, NodeCountLargerThanData) {
  EXPECT_THAT(msh(kMsh2Head + "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"),
              HasSubstr("line 10: expected node number (an integer), got '$EndNodes'"));
}

TEST(IoMalformed, ElementCountSmallerThanData) {
  EXPECT_THAT(msh(kMsh2Head + kMsh2Nodes + "$Elements\n1\n1 4 2 1 1 1 2 3 4\n2 4 2 1 1 1 2 3 4\n$EndElements\n"),
              HasSubstr("line 14: expected $EndElements, got '2'"));
}

TEST(IoMalformed, NanCoordinate) {
  EXPECT_THAT(msh(kMsh2Head + "$Nodes\n2\n1 0 0 0\n2 1 nan 0\n$EndNodes\n"),
              HasSubstr("t.msh: line 7: coordinate is not finite (nan)"));
}

TEST(IoMalformed, UnknownElementType) {
  EXPECT_THAT(msh(kMsh2Head + kMsh2Nodes + "$Elements\n1\n1 77 2 1 1 1 2 3 4\n$EndElements\n"),
              HasSubstr("line 13: unknown element type 77"));
}

// A hexahedron is read (a mixed mesh); the tet path refuses it naming its cells.
TEST(IoMalformed, HexIsReadAndRefusedByTheTetPath) {
  const TetSoup soup = read_msh(kMsh2Head + kMsh2Nodes + "$Elements\n1\n1 5 2 1 1 1 2 3 4 1 2 3 4\n$EndElements\n", "t.msh");
  ASSERT_EQ(soup.other_cells.size(), 1u);
  EXPECT_EQ(soup.other_cells[0].type, CellType::Hex);
  EXPECT_THAT(error_of([&] { classify(soup); }),
              HasSubstr("t.msh: a mixed mesh (1 hexahedron): classify() takes tetrahedra only"));
}

TEST(IoMalformed, NonIntegerTag) {
  EXPECT_THAT(msh(kMsh2Head + kMsh2Nodes + "$Elements\n1\n1 4 2 one 1 1 2 3 4\n$EndElements\n"),
              HasSubstr("line 13: expected tag (an integer), got 'one'"));
}

TEST(IoMalformed, UndefinedNode) {
  EXPECT_THAT(msh(kMsh2Head + kMsh2Nodes + "$Elements\n1\n12 4 2 1 1 1 2 3 99\n$EndElements\n"),
              HasSubstr("line 13: element 12: node 99 is not defined in $Nodes"));
}

TEST(IoMalformed, HugeCountIsAnErrorNotAnAllocation) {
  EXPECT_THAT(msh(kMsh2Head + "$Nodes\n1000000000000\n1 0 0 0\n$EndNodes\n"),
              HasSubstr("line 5: number of nodes 1000000000000 out of range"));
  EXPECT_THAT(msh(kMsh2Head + "$Nodes\n4000000000\n1 0 0 0\n$EndNodes\n"),
              HasSubstr("line 5: file too short for 4000000000 node records"));
}

TEST(IoMalformed, MissingSection) {
  EXPECT_THAT(msh(kMsh2Head + kMsh2Nodes),
              HasSubstr("t.msh: end of file: the file holds no tetrahedra (no $Elements section after $Nodes"));
  EXPECT_THAT(msh(kMsh2Head + "$Elements\n0\n$EndElements\n"), HasSubstr("line 4: $Elements before $Nodes"));
  EXPECT_THAT(msh(kMsh2Head + "$Comments\nno end"), HasSubstr("section $Comments is not closed by $EndComments"));
}

TEST(IoMalformed, Msh4DuplicatedNodeTag) {
  EXPECT_THAT(msh(kMsh4Head + "$Nodes\n1 2 1 2\n3 1 0 2\n7\n7\n0 0 0\n1 0 0\n$EndNodes\n"),
              HasSubstr("line 8: node tag 7 defined twice"));
}

TEST(IoMalformed, Msh4BlockSizesDisagreeWithHeader) {
  EXPECT_THAT(msh(kMsh4Head + "$Nodes\n1 1 1 2\n3 1 0 2\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n"),
              HasSubstr("line 6: node block of 2 nodes exceeds the 1 nodes announced"));
  EXPECT_THAT(msh(kMsh4Head + "$Nodes\n1 3 1 3\n3 1 0 2\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n"),
              HasSubstr("$Nodes announces 3 nodes but its blocks hold 2"));
}

TEST(IoMalformed, Msh4VolumeMissingFromEntities) {
  EXPECT_THAT(msh(kMsh4Head + "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 1 10 0\n$EndEntities\n" +
                  "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n" +
                  "$Elements\n1 1 1 1\n3 5 4 1\n1 1 2 3 4\n$EndElements\n"),
              HasSubstr("line 22: entity (3, 5) is not in $Entities"));
}

TEST(IoMalformed, Msh4BoundingEntityNotInEntities) {
  // Curve 1 from point 1 to point -2 (Gmsh signs the end point), point 2 missing.
  EXPECT_THAT(msh(kMsh4Head + "$Entities\n1 1 0 0\n1 0 0 0 0\n1 0 0 0 1 0 0 0 2 1 -2\n$EndEntities\n"),
              HasSubstr("t.msh: line 7: curve 1 is bounded by point -2, which is not in $Entities (no point 2"));
  EXPECT_THAT(msh(kMsh4Head + "$Entities\n0 0 1 1\n5 0 0 0 1 1 1 0 0\n9 0 0 0 1 1 1 0 1 6\n$EndEntities\n"),
              HasSubstr("line 7: volume 9 is bounded by surface 6, which is not in $Entities"));
  // Binary: counts as size_t, tags as int.
  auto bytes = [](auto v) { return std::string(reinterpret_cast<const char*>(&v), sizeof v); };
  std::string bin = "$MeshFormat\n4.1 1 8\n" + bytes(std::int32_t(1)) + "\n$EndMeshFormat\n$Entities\n";
  for (std::uint64_t n : {1, 1, 0, 0}) bin += bytes(n);
  bin += bytes(std::int32_t(1)) + std::string(24, '\0') + bytes(std::uint64_t(0));  // point 1
  bin += bytes(std::int32_t(1)) + std::string(48, '\0') + bytes(std::uint64_t(0)) + bytes(std::uint64_t(2)) +
         bytes(std::int32_t(1)) + bytes(std::int32_t(-4));  // curve 1 from 1 to -4
  const std::size_t after = bin.size();
  EXPECT_THAT(msh(bin + "\n$EndEntities\n"),
              HasSubstr("t.msh: byte " + std::to_string(after) + ": curve 1 is bounded by point -4"));
}

TEST(IoMalformed, Msh4ParametricNodes) {
  EXPECT_THAT(msh(kMsh4Head + "$Nodes\n1 1 1 1\n2 1 1 1\n1\n0 0 0 0.5 0.5\n$EndNodes\n"),
              HasSubstr("line 6: parametric nodes are not supported"));
}

TEST(IoMalformed, BinaryTruncatedInsideNodes) {
  const std::string whole = read_file_bytes(kData + "/cube5_bin.msh");
  const std::size_t nodes = whole.find("$Nodes");
  EXPECT_THAT(msh(whole.substr(0, nodes + 200)),
              AllOf(HasSubstr("t.msh: byte "), HasSubstr("file too short for 8 node records")));
  const std::size_t eof = whole.find("\n$EndNodes") - 10;
  EXPECT_THAT(msh(whole.substr(0, eof)), HasSubstr("file too short for 4 node records (at least 128 bytes, 118 remain)"));
  EXPECT_THAT(msh(whole.substr(0, whole.find("4.1 1 8\n") + 10)),
              HasSubstr("byte 20: file ends inside the endianness check of $MeshFormat"));
}

TEST(IoMalformed, BinaryHugeCount) {
  std::string bytes = read_file_bytes(kData + "/cube5_bin.msh");
  const std::size_t at = bytes.find("$Nodes\n") + 7 + 8;  // the number of nodes (size_t)
  const std::uint64_t huge = 1ull << 40;
  bytes.replace(at, 8, reinterpret_cast<const char*>(&huge), 8);
  EXPECT_THAT(msh(bytes), AllOf(HasSubstr("byte "), HasSubstr("the number of nodes 1099511627776 out of range")));
}

TEST(IoMalformed, BinaryNanAndEndianness) {
  std::string bytes = read_file_bytes(kData + "/cube5_v2_bin.msh");
  const std::size_t at = bytes.find("$Nodes\n8\n") + 9 + 4;  // x of node 1
  const double nan = std::numeric_limits<double>::quiet_NaN();
  bytes.replace(at, 8, reinterpret_cast<const char*>(&nan), 8);
  EXPECT_THAT(msh(bytes), HasSubstr("byte " + std::to_string(at) + ": coordinate is not finite (nan)"));
  std::string swapped = read_file_bytes(kData + "/cube5_v2_bin.msh");
  const std::size_t one = swapped.find("2.2 1 8\n") + 8;
  swapped[one] = 0;
  swapped[one + 3] = 1;
  EXPECT_THAT(msh(swapped), HasSubstr("other endianness"));
}

TEST(IoMalformed, BinaryElementBlockLargerThanCount) {
  std::string bytes = read_file_bytes(kData + "/cube5_v2_bin.msh");
  const std::size_t at = bytes.find("$Elements\n21\n") + 13 + 4;  // count of the first block
  const std::int32_t too_many = 40;
  bytes.replace(at, 4, reinterpret_cast<const char*>(&too_many), 4);
  EXPECT_THAT(msh(bytes), HasSubstr("element block of 40 elements does not fit the 21 elements left"));
}

TEST(IoMalformed, MshWithoutTetsIsEmpty) {
  EXPECT_THAT(msh(kMsh2Head + kMsh2Nodes + "$Elements\n0\n$EndElements\n"),
              HasSubstr("t.msh: line 11: the file holds no tetrahedra ($Elements has none)"));
  EXPECT_THAT(msh(kMsh2Head + kMsh2Nodes + "$Elements\n1\n1 2 2 1 1 1 2 3\n$EndElements\n"),
              HasSubstr("line 11: the file holds no tetrahedra ($Elements has none, only 1 triangle, line or point)"));
  EXPECT_THAT(msh(kMsh4Head + "$Nodes\n0 0 0 0\n$EndNodes\n$Elements\n0 0 0 0\n$EndElements\n"),
              HasSubstr("line 7: the file holds no tetrahedra"));
  EXPECT_THAT(msh(kMsh2Head + "$Elements\n0\n$EndElements\n"), HasSubstr("$Elements before $Nodes"));
  EXPECT_THAT(msh(kMsh2Head), HasSubstr("end of file: the file holds no tetrahedra (no $Nodes and no $Elements section)"));
}

// ---- NUL bytes where text is expected, in every text format
TEST(IoMalformed, NulByteInText) {
  using namespace std::string_literals;  // the inputs hold NUL bytes
  const std::string nul = "NUL byte where text was expected";
  EXPECT_THAT(msh(kMsh2Head + "$Nodes\n2\n1 0 0 0\n2 1 0\0 0\n$EndNodes\n"s), HasSubstr("t.msh: line 7: " + nul));
  EXPECT_THAT(msh(kMsh2Head + "$Comments\n\0\0\0"s), HasSubstr("section $Comments is not closed"));
  EXPECT_THAT(msh(kMsh2Head + "$PhysicalNames\n1\n3 1 \"a\0b\"\n"s), HasSubstr("t.msh: line 6: " + nul));
  EXPECT_THAT(medit(kMeditHead + "Tetra\0hedra\n1\n1 2 3 4 1\n"s), HasSubstr("t.mesh: line 9: " + nul));
  EXPECT_THAT(medit("# comment\0\nDimension 3\n"s), HasSubstr("t.mesh: line 1: " + nul));
  EXPECT_THAT(tetgen(kNode, "1 4 0\n0 0 1 2\0 3\n"s), HasSubstr("t.ele: line 2: " + nul));
  EXPECT_THAT(tetgen(kNode, "1 4 0\n0 0 1 2 3\n", "1 1\n0 0 1 2 5 \0\n"s), HasSubstr("t.face: line 2: " + nul));
  EXPECT_THAT(vtu(kVtuHeadForNul + "<Piece NumberOfPoints=\"1\"\0"s), HasSubstr("t.vtu: line 2: " + nul));
}

// ---- Medit
TEST(IoMalformed, MeditVertexIndexOutOfRange) {
  EXPECT_THAT(medit(kMeditHead + "Tetrahedra\n1\n1 2 3 99 1\nEnd\n"),
              HasSubstr("t.mesh: line 11: vertex index 99 out of range (1..4)"));
}

TEST(IoMalformed, MeditInfCoordinateAndShortRecord) {
  EXPECT_THAT(medit("Dimension 3\nVertices\n1\n0 -inf 0 0\n"), HasSubstr("line 4: coordinate is not finite (-inf)"));
  EXPECT_THAT(medit(kMeditHead + "Tetrahedra\n1\n1 2 3\nEnd\n"),
              HasSubstr("line 12: expected vertex index (an integer), got 'End'"));
}

TEST(IoMalformed, MeditUnknownKeywordAndDimension) {
  EXPECT_THAT(medit(kMeditHead + "SolAtVertices\n4\n1 1\n"), HasSubstr("line 9: unknown keyword 'SolAtVertices'"));
  EXPECT_THAT(medit("MeshVersionFormatted 2\nDimension 2\n"), HasSubstr("line 2: Dimension 2 not supported"));
  EXPECT_THAT(medit(kMeditHead + "TetrahedraP2\n0\n"), HasSubstr("unsupported element kind TetrahedraP2"));
  EXPECT_THAT(medit(kMeditHead + "End\n"), HasSubstr("end of file: the file holds no tetrahedra (no Tetrahedra section)"));
}

TEST(IoMalformed, MeditEmptyOrWithoutTets) {
  EXPECT_THAT(medit(""), HasSubstr("t.mesh: the file is empty"));
  EXPECT_THAT(medit("# only a comment\n\n"), HasSubstr("t.mesh: the file is empty"));
  EXPECT_THAT(medit("MeshVersionFormatted 2\nDimension 3\nVertices\n0\nTetrahedra\n0\nEnd\n"),
              HasSubstr("t.mesh: line 5: the file holds no tetrahedra (its Tetrahedra section is empty)"));
  EXPECT_THAT(medit("MeshVersionFormatted 2\nDimension 3\nTetrahedra\n0\n"),
              HasSubstr("line 3: the file holds no tetrahedra (its Tetrahedra section is empty)"));
  EXPECT_THAT(medit("MeshVersionFormatted 2\nDimension 3\nEnd\n"),
              HasSubstr("end of file: the file holds no tetrahedra (no Vertices and no Tetrahedra section)"));
  EXPECT_THAT(medit(kMeditHead + "Triangles\n1\n1 2 3 7\nEnd\n"),
              HasSubstr("the file holds no tetrahedra (no Tetrahedra section, only 1 triangle, edge or corner)"));
  EXPECT_THAT(medit(kMeditHead + "Vertices\n0\n"), HasSubstr("line 9: second Vertices section"));
}

TEST(IoMalformed, TriangleWithRepeatedVertex) {
  EXPECT_THAT(medit(kMeditHead + "Tetrahedra\n1\n1 2 3 4 1\nTriangles\n1\n1 2 1 5\n"),
              HasSubstr("line 14: triangle has a repeated vertex (1)"));
  EXPECT_THAT(msh(kMsh2Head + kMsh2Nodes + "$Elements\n1\n3 2 2 0 1 1 2 2\n$EndElements\n"),
              HasSubstr("line 13: element 3: triangle has a repeated vertex (2)"));
  EXPECT_THAT(tetgen(kNode, "1 4 0\n0 0 1 2 3\n", "1 1\n0 0 3 3 2\n"),
              HasSubstr("t.face: line 2: face has a repeated vertex (4)"));
}

// ---- TetGen
TEST(IoMalformed, TetGenIndexOutOfRangeAndSequence) {
  EXPECT_THAT(tetgen(kNode, "1 4 0\n0 0 1 2 9\n"), HasSubstr("t.ele: line 2: node index 9 out of range (0..3)"));
  EXPECT_THAT(tetgen("2 3 0 0\n0 0 0 0\n5 1 0 0\n", "1 4 0\n0 0 1 2 3\n"),
              HasSubstr("t.node: line 3: node index 5 out of sequence (expected 1)"));
}

TEST(IoMalformed, TetGenSecondOrderAndRegionNotInteger) {
  EXPECT_THAT(tetgen(kNode, "1 10 0\n"), HasSubstr("t.ele: line 1: tetrahedra with 10 nodes not supported"));
  EXPECT_THAT(tetgen(kNode, "1 4 1\n0 0 1 2 3 1.5\n"), HasSubstr("line 2: region attribute is not an integer"));
}

TEST(IoMalformed, TetGenEmpty) {
  EXPECT_THAT(tetgen("", "1 4 0\n0 0 1 2 3\n"), HasSubstr("t.node: the file is empty"));
  EXPECT_THAT(tetgen("0 3 0 0\n", "1 4 0\n0 0 1 2 3\n"),
              HasSubstr("t.node: line 1: the file holds no tetrahedra (its node count is 0)"));
  EXPECT_THAT(tetgen(kNode, "0 4 0\n"), HasSubstr("t.ele: line 1: the file holds no tetrahedra (its tetrahedron count is 0)"));
  EXPECT_THAT(tetgen(kNode, "# nothing\n"), HasSubstr("t.ele: the file is empty"));
}

TEST(IoMalformed, TetGenCountsDisagree) {
  EXPECT_THAT(tetgen(kNode, "2 4 0\n0 0 1 2 3\n"), HasSubstr("t.ele: line 1: file too short for 2 tetrahedron records"));
  EXPECT_THAT(tetgen(kNode, "1 4 0\n0 0 1 2 3\n1 0 1 2 3\n"), HasSubstr("line 3: more data after the 1 tetrahedra"));
  EXPECT_THAT(tetgen(kNode, "1 4 0\n0 0 1 2 3\n", "1 1\n0 0 1 7 2\n"),
              HasSubstr("t.face: line 2: node index 7 out of range (0..3)"));
}

// ---- VTU
const std::string kVtuHead = R"(<VTKFile type="UnstructuredGrid"><UnstructuredGrid>)";
std::string vtu_piece(const std::string& cells, const std::string& types, const std::string& extra = "") {
  return kVtuHead + R"(<Piece NumberOfPoints="4" NumberOfCells="1">
<Points><DataArray type="Float64" NumberOfComponents="3">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>
<Cells><DataArray type="Int32" Name="connectivity">)" + cells + R"(</DataArray>
<DataArray type="Int32" Name="offsets">4</DataArray><DataArray type="Int32" Name="types">)" + types +
         "</DataArray></Cells>" + extra + "</Piece></UnstructuredGrid></VTKFile>";
}

TEST(IoMalformed, VtuCompressedAndAppended) {
  const std::string tail = "</UnstructuredGrid></VTKFile>";
  EXPECT_THAT(vtu(R"(<VTKFile type="UnstructuredGrid" compressor="vtkLZMADataCompressor"></VTKFile>)"),
              HasSubstr("t.vtu: line 1: compressor 'vtkLZMADataCompressor' not supported"));
  EXPECT_THAT(vtu(kVtuHead + "\n<AppendedData encoding=\"raw\">xx</AppendedData>" + tail),
              HasSubstr("line 2: AppendedData does not start with '_'"));
}

TEST(IoMalformed, VtuCellTypeAndIndex) {
  EXPECT_THAT(vtu(vtu_piece("0 1 2 3", "42")), HasSubstr("cell 0: unsupported VTK cell type 42"));
  EXPECT_THAT(vtu(vtu_piece("0 1 2 3", "12")), HasSubstr("cell 0: expected 8 node indices, got 4"));  // a hexahedron
  EXPECT_THAT(vtu(vtu_piece("0 1 2 4", "10")), HasSubstr("line 3: cell 0: node index 4 out of range (0..3)"));
  EXPECT_THAT(vtu(vtu_piece("0 1 2 3", "10", R"(<CellData><DataArray type="Int32" Name="region">1 2</DataArray></CellData>)")),
              HasSubstr("region array 'region' has 2 values for 1 cells"));
}

TEST(IoMalformed, VtuEmptyOrWithoutTets) {
  EXPECT_THAT(vtu(" \n"), HasSubstr("t.vtu: the file is empty"));
  std::string triangle = vtu_piece("0 1 2", "5");
  triangle.replace(triangle.find("offsets\">4<"), 11, "offsets\">3<");
  EXPECT_THAT(vtu(triangle), HasSubstr("line 1: the file holds no tetrahedra (none of its 1 cells is a tetra)"));
  EXPECT_THAT(vtu(kVtuHead + R"(<Piece NumberOfPoints="0" NumberOfCells="0"><Points><DataArray type="Float64" )" +
                  R"(NumberOfComponents="3"></DataArray></Points><Cells><DataArray type="Int32" Name="connectivity">)" +
                  R"(</DataArray><DataArray type="Int32" Name="offsets"></DataArray><DataArray type="UInt8" )" +
                  R"(Name="types"></DataArray></Cells></Piece></UnstructuredGrid></VTKFile>)"),
              HasSubstr("the file holds no tetrahedra (NumberOfCells is 0)"));
}

TEST(IoMalformed, VtuBinarySizeMismatchAndTruncation) {
  // Header claims 16 bytes (UInt32 header 0x10) but only 4 follow.
  EXPECT_THAT(vtu(kVtuHead + R"(<Piece NumberOfPoints="1" NumberOfCells="0"><Points>
<DataArray type="Float64" NumberOfComponents="3" format="binary">EAAAAAAAAAA=</DataArray></Points></Piece></UnstructuredGrid></VTKFile>)"),
              HasSubstr("line 2: DataArray '(unnamed)': size header says 16 bytes but 4 bytes of Float64 follow"));
  EXPECT_THAT(vtu(kVtuHead + "<Piece NumberOfPoints=\"1\" NumberOfCells=\"0\">"), HasSubstr("file ends inside <Piece>"));
  EXPECT_THAT(vtu(kVtuHead + "<Piece NumberOfPoints=\"99999999999\" NumberOfCells=\"0\"></Piece></UnstructuredGrid></VTKFile>"),
              HasSubstr("NumberOfPoints 99999999999 out of range"));
}

// ---- geometric faults, found by classify() after a successful read
const std::string kSix =
    "MeshVersionFormatted 2\nDimension 3\nVertices\n7\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 -1 0\n"
    "0.2 0.2 1 0\n1 1 0 0\n";

TEST(IoMalformed, InvertedTet) {
  // One tet of two oriented against the other (a lone inverted tet is a mesh
  // of the other convention, flipped: io_producers_test).
  EXPECT_THAT(medit_then_classify(kSix + "Tetrahedra\n2\n1 2 3 4 1\n1 2 3 5 1\nEnd\n"),
              HasSubstr("t.mesh: tet 2: tet 2 is inverted (negative orientation)"));
}
TEST(IoMalformed, ZeroVolumeTet) {
  EXPECT_THAT(medit_then_classify(kSix + "Tetrahedra\n2\n1 2 3 4 1\n1 2 3 7 1\nEnd\n"),
              AllOf(HasSubstr("tet 2"), HasSubstr("zero volume")));
}
TEST(IoMalformed, DuplicatedTet) {
  EXPECT_THAT(medit_then_classify(kSix + "Tetrahedra\n2\n1 2 3 4 1\n1 2 3 4 1\nEnd\n"), HasSubstr("duplicated tet"));
}
TEST(IoMalformed, NonConformalTriangleOfThreeTets) {
  EXPECT_THAT(medit_then_classify(kSix + "Tetrahedra\n3\n1 2 3 4 1\n1 3 2 5 1\n1 2 3 6 1\nEnd\n"),
              HasSubstr("non-conformal"));
}

}  // namespace
}  // namespace polydual
