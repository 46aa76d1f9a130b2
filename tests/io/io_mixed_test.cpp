// Mixed and surface meshes through the readers to the primal: Gmsh meshes
// made at test time (an extruded prism layer, a transfinite hexahedral box,
// hexahedra joined to tets through pyramids, a surface network), Medit and
// VTU files written here; the tet path refuses them naming their cells.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "require_tool.h"
#include "classify/classify.h"
#include "classify/classify_primal.h"
#include "core/error.h"
#include "io/medit_io.h"
#include "io/read_any_mesh.h"
#include "io/read_tet_mesh.h"
#include "io/vtu_reader.h"
#include "mesh/cell_soup.h"
#include "run_command.h"
#include "scratch_dir.h"

using namespace polydual;
using ::testing::HasSubstr;

namespace {

std::filesystem::path scratch() { return test::scratch_dir(); }
std::string write(const std::string& name, const std::string& text) {
  const auto p = scratch() / name;
  std::ofstream(p) << text;
  return p.string();
}
bool have_gmsh() {
  static const bool have = std::system("gmsh --version > /dev/null 2>&1") == 0;
  return have;
}
std::string gmsh_mesh(const std::string& name, const std::string& geo, const std::string& options, int dim = 3) {
  const std::string g = write(name + ".geo", geo), out = (scratch() / (name + ".msh")).string();
  const std::string cmd = "gmsh -" + std::to_string(dim) + " " + g + " " + options + " -o " + out + " > " + out + ".log 2>&1";
  if (std::system(cmd.c_str()) != 0) ADD_FAILURE() << "failed: " << cmd;
  return out;
}
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

std::size_t count(const TetSoup& s, CellType t) { return mixed_cell_counts(s)[std::size_t(t)]; }

// The primal is conformal and closed: every local face is matched once or
// lies on the boundary, and the boundary faces form a closed surface (each
// boundary edge on an even number of them).
void expect_consistent(const PrimalMesh& m) {
  std::size_t local = 0, boundary = 0;
  for (std::size_t c = 0; c < m.num_cells(); ++c)
    for (int i = 0; i < m.cell_descriptor(PrimalCellId(c)).num_faces; ++i) {
      ++local;
      boundary += !m.cell_neighbor(PrimalCellId(c), i).valid();
    }
  EXPECT_EQ(local, 2 * m.num_faces() - boundary);
  for (std::size_t e = 0; e < m.num_edges(); ++e)
    for (const EdgeChain& ch : m.edge_chains(EdgeId(e))) EXPECT_EQ(ch.faces.size(), ch.cells.size() + 1);
}

const char* kExtruded =
    "SetFactory(\"Built-in\");\nPoint(1)={0,0,0,0.3};Point(2)={1,0,0,0.3};Point(3)={1,1,0,0.3};Point(4)={0,1,0,0.3};\n"
    "Line(1)={1,2};Line(2)={2,3};Line(3)={3,4};Line(4)={4,1};Curve Loop(1)={1,2,3,4};Plane Surface(1)={1};\n"
    "out[] = Extrude {0,0,0.2} { Surface{1}; Layers{3}; Recombine; };\nPhysical Volume(\"layer\") = {out[1]};\n";
const char* kHexBox =
    "SetFactory(\"OpenCASCADE\");\nBox(1) = {0,0,0,1,1,1};\nTransfinite Curve{:} = 4;\nTransfinite Surface{:};\n"
    "Recombine Surface{:};\nTransfinite Volume{1};\n";
// Hexahedra extruded from a recombined square, tets on top: Gmsh joins the
// quads to the tets with pyramids.
const char* kHexPyramidTet =
    "SetFactory(\"Built-in\");\nPoint(1)={0,0,0,0.3};Point(2)={1,0,0,0.3};Point(3)={1,1,0,0.3};Point(4)={0,1,0,0.3};\n"
    "Line(1)={1,2};Line(2)={2,3};Line(3)={3,4};Line(4)={4,1};Curve Loop(1)={1,2,3,4};Plane Surface(1)={1};\n"
    "Transfinite Curve{1,2,3,4}=4;Transfinite Surface{1};Recombine Surface{1};\n"
    "out[] = Extrude {0,0,0.5} { Surface{1}; Layers{2}; Recombine; };\n"
    "out2[] = Extrude {0,0,0.5} { Surface{out[0]}; };\n"
    "Physical Volume(\"hexes\") = {out[1]};\nPhysical Volume(\"tets\") = {out2[1]};\n";

}  // namespace

TEST(IoMixed, GmshExtrudedPrismLayerReachesThePrimal) {
  if (!have_gmsh()) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  for (const std::string options : {"-format msh41", "-format msh22", "-format msh41 -bin", "-format msh22 -bin"}) {
    SCOPED_TRACE(options);
    const std::string path = gmsh_mesh("prisms", kExtruded, options);
    const TetSoup soup = read_tet_mesh(path);
    EXPECT_TRUE(soup.tets.empty());
    EXPECT_EQ(count(soup, CellType::Prism), soup.other_cells.size());
    EXPECT_GT(soup.other_cells.size(), 0u);
    EXPECT_EQ(soup.other_cells.size() % 3, 0u);  // three layers of one triangulation
    const PrimalMesh m = build_primal(cell_soup(soup));
    EXPECT_EQ(m.num_cells(), soup.other_cells.size());
    expect_consistent(m);
    EXPECT_THAT(error_of([&] { classify(soup); }),
                HasSubstr(": a mixed mesh (" + std::to_string(soup.other_cells.size()) + " prisms): classify() takes tetrahedra only"));
  }
}

TEST(IoMixed, GmshTransfiniteHexBoxAndHexPyramidTetBlock) {
  if (!have_gmsh()) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  const TetSoup hexes = read_tet_mesh(gmsh_mesh("hexbox", kHexBox, "-format msh41"));
  EXPECT_EQ(count(hexes, CellType::Hex), 27u);
  EXPECT_EQ(hexes.quads.size(), 54u);  // 6 sides of 3 x 3 boundary quadrangles
  const PrimalMesh h = build_primal(cell_soup(hexes));
  EXPECT_EQ(h.num_vertices(), 64u);
  EXPECT_EQ(h.num_faces(), 108u);  // 3 * 4 * 3 * 3
  EXPECT_EQ(h.num_edges(), 144u);  // 3 * 3 * 4 * 4
  expect_consistent(h);
  const TetSoup mixed = read_tet_mesh(gmsh_mesh("hexpyrtet", kHexPyramidTet, "-format msh22"));
  EXPECT_EQ(count(mixed, CellType::Hex), 18u);
  EXPECT_GT(count(mixed, CellType::Pyramid), 0u);
  EXPECT_GT(count(mixed, CellType::Tet), 0u);
  const PrimalMesh m = build_primal(cell_soup(mixed));
  expect_consistent(m);
  // Every quadrangle between the hex layer and the tets is a pyramid's base:
  // shared whole by a hexahedron and a pyramid.
  std::size_t shared_quads = 0;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const PrimalFaceId ff(f);
    if (m.face_vertices(ff).size() != 4 || !m.face_cell(ff, 1).valid()) continue;
    const CellType a = m.cell_type(m.face_cell(ff, 0)), b = m.cell_type(m.face_cell(ff, 1));
    shared_quads += (a == CellType::Pyramid) != (b == CellType::Pyramid);
  }
  EXPECT_EQ(shared_quads, count(mixed, CellType::Pyramid));
  const auto r = polydual::testing::run_polydual("convert " + (scratch() / "hexpyrtet.msh").string() + " -o " +
                                       (scratch() / "out.vtu").string());
  // convert makes its dual (pipeline/convert_mixed.h) and says it was mixed.
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("mixed mesh (\"" + std::to_string(count(mixed, CellType::Tet)) + " tetrahedra, " +
                               std::to_string(count(mixed, CellType::Pyramid)) + " pyramids, 18 hexahedra\")"));
  EXPECT_TRUE(std::filesystem::exists(scratch() / "out.vtu"));
  const auto info = polydual::testing::run_polydual("info --json " + (scratch() / "hexpyrtet.msh").string());
  EXPECT_EQ(info.code, 0) << info.out;
  EXPECT_THAT(info.out, HasSubstr("\"hexahedra\": 18"));
}

TEST(IoMixed, GmshSurfaceNetworkIsASurfacePrimal) {
  if (!have_gmsh()) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  const std::string geo =
      "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {0,0,0,1,1};\nRectangle(2) = {0.5,-0.5,-0.5,1,1};\n"
      "Rotate {{1,0,0},{0.5,0,0},Pi/2} { Surface{2}; }\n"
      "BooleanFragments{ Surface{1}; Delete; }{ Surface{2}; Delete; }\nMesh.MeshSizeMax = 0.25;\n";
  const std::string path = gmsh_mesh("network", geo, "-format msh41", 2);
  EXPECT_THAT(error_of([&] { read_tet_mesh(path); }), HasSubstr("the file holds no tetrahedra"));
  const TetSoup soup = read_any_mesh(path);
  ASSERT_GT(soup.triangles.size(), 0u);
  const PrimalMesh m = build_primal(cell_soup(soup));
  EXPECT_EQ(m.dim(), 2);
  EXPECT_EQ(m.num_cells(), soup.triangles.size());
  // The crossing line: edges with four triangles around them, on a model edge.
  std::size_t crossing = 0;
  for (std::size_t e = 0; e < m.num_edges(); ++e)
    if (m.edge_cells(EdgeId(e)).size() == 4) {
      ++crossing;
      EXPECT_EQ(m.edge_class(EdgeId(e)).dim, 1);
    }
  EXPECT_GT(crossing, 0u);
}

// A Medit file: two hexahedra stacked, a prism on top, a pyramid beside.
TEST(IoMixed, MeditHexahedraPrismsPyramids) {
  const std::string mesh =
      "MeshVersionFormatted 2\nDimension 3\nVertices\n13\n"
      "0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n0 0 1 0\n1 0 1 0\n1 1 1 0\n0 1 1 0\n"
      "0 0 2 0\n1 0 2 0\n1 1 2 0\n0 1 2 0\n0.5 -0.5 0.5 0\n"
      "Hexahedra\n2\n1 2 3 4 5 6 7 8 1\n5 6 7 8 9 10 11 12 1\n"
      "Pyramids\n1\n1 5 6 2 13 2\nEnd\n";
  const TetSoup soup = read_medit(mesh, "m.mesh");
  ASSERT_EQ(soup.other_cells.size(), 3u);
  EXPECT_EQ(soup.other_cells[2].type, CellType::Pyramid);
  const PrimalMesh m = build_primal(cell_soup(soup));
  expect_consistent(m);
  EXPECT_EQ(m.num_faces(), 6u + 6u + 5u - 2u);
  EXPECT_THAT(error_of([&] { classify(soup); }), HasSubstr("m.mesh: a mixed mesh (1 pyramid, 2 hexahedra)"));
}

// A VTU file with a wedge in VTK's order (its (0, 1, 2) points away from
// (3, 4, 5): the mirror of Gmsh's prism) on a hexahedron's x = 1 side, and a pyramid
// (base towards the apex, as VTK has it) under it: read, reordered, conformal.
TEST(IoMixed, VtuWedgeHexahedronPyramid) {
  const std::string vtu =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n<UnstructuredGrid>\n"
      "<Piece NumberOfPoints=\"11\" NumberOfCells=\"3\">\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\">"
      "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1 2 0 0.5 2 1 0.5 0.5 0.5 -1</DataArray></Points>\n"
      "<Cells><DataArray type=\"Int64\" Name=\"connectivity\">0 1 2 3 4 5 6 7  1 8 5 2 9 6  0 3 2 1 10</DataArray>\n"
      "<DataArray type=\"Int64\" Name=\"offsets\">8 14 19</DataArray>\n"
      "<DataArray type=\"UInt8\" Name=\"types\">12 13 14</DataArray></Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  const TetSoup soup = read_vtu(vtu, "w.vtu");
  ASSERT_EQ(soup.other_cells.size(), 3u);
  std::vector<std::string> warnings;
  const PrimalMesh m = build_primal(cell_soup(soup), &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings.front();  // VTK's wedge, reordered by the reader, is positive
  expect_consistent(m);
  EXPECT_EQ(m.num_faces(), 6u + 5u + 5u - 2u);
  EXPECT_THAT(error_of([&] { classify(soup); }), HasSubstr("a mixed mesh (1 pyramid, 1 prism, 1 hexahedron)"));
}
