// `polydual convert` of surface meshes (pipeline/convert_surface.h): a Gmsh
// fracture network made at test time (OpenCASCADE BooleanFragments of two
// rectangles and a disk), the VTU of VTK_POLYGON cells read back, the same
// bytes for any thread count, and bad input (a degenerate triangle, an
// OpenFOAM output) refused with a clear error and no output.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "generate/fracture_surfaces.h"
#include "io/vtk_xml.h"
#include "pipeline/convert_surface.h"
#include "require_tool.h"
#include "run_command.h"
#include "scratch_dir.h"

using namespace polydual;
using polydual::testing::run_polydual;
using ::testing::HasSubstr;

namespace {

std::filesystem::path scratch() { return test::scratch_dir(); }
std::string write(const std::string& name, const std::string& text) {
  const auto p = scratch() / name;
  std::ofstream(p) << text;
  return p.string();
}
std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Two crossing squares and a disk crossing one of them along a segment that
// ends inside it, fragmented so that the meshes are conformal on the lines.
const char* kNetworkGeo = R"(SetFactory("OpenCASCADE");
Rectangle(1) = {-1, -1, 0, 2, 2};
Rectangle(2) = {-1, -1, 0, 2, 2};
Rotate {{1, 0, 0}, {0, 0, 0}, Pi/2} { Surface{2}; }
Disk(3) = {0.3, 0.5, 0, 0.4, 0.4};
Rotate {{0, 1, 0}, {0.3, 0.5, 0}, Pi/2} { Surface{3}; }
BooleanFragments{ Surface{1, 2, 3}; Delete; }{}
Mesh.MeshSizeMax = 0.08;
Mesh.RandomSeed = 1;
General.NumThreads = 1;
)";

std::string gmsh_network() {
  const std::string geo = write("network.geo", kNetworkGeo);
  const std::string msh = (scratch() / "network.msh").string();
  const int rc = std::system(("gmsh -2 -format msh41 '" + geo + "' -o '" + msh + "' > /dev/null 2>&1").c_str());
  EXPECT_EQ(rc, 0);
  return msh;
}

struct VtuCounts {
  std::int64_t points = 0, cells = 0;
  std::vector<std::int64_t> types, valid, offsets, connectivity;
};
VtuCounts read_vtu(const std::string& path) {
  const std::string bytes = slurp(path);
  io::vtkxml::VtkXml x(bytes, path, "UnstructuredGrid");
  VtuCounts c;
  c.points = x.count_attr(x.piece(), "NumberOfPoints");
  c.cells = x.count_attr(x.piece(), "NumberOfCells");
  c.types = x.integers(*x.find_array("Cells", "types"));
  c.offsets = x.integers(*x.find_array("Cells", "offsets"));
  c.connectivity = x.integers(*x.find_array("Cells", "connectivity"));
  c.valid = x.integers(*x.find_array("CellData", "valid"));
  EXPECT_NE(x.find_array("CellData", "surface"), nullptr);
  EXPECT_NE(x.find_array("CellData", "primal_vertex"), nullptr);
  EXPECT_NE(x.find_array("PointData", "class_dim"), nullptr);
  EXPECT_NE(x.find_array("PointData", "class_tag"), nullptr);
  EXPECT_EQ(x.reals(*x.find_array("Points")).size(), std::size_t(3 * c.points));
  return c;
}

}  // namespace

TEST(SurfaceConvert, GmshNetworkConvertsWithEveryPolygonValid) {
  if (!polydual::test::have_command("gmsh")) POLYDUAL_MISSING_TOOL("gmsh not found (package gmsh)");
  const std::string msh = gmsh_network();
  const std::string out = (scratch() / "network.vtu").string();
  const auto r = run_polydual("convert '" + msh + "' -o '" + out + "' --json --quiet");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("\"invalid\": 0"));
  const VtuCounts c = read_vtu(out);
  EXPECT_GT(c.cells, 500);
  EXPECT_THAT(r.out, HasSubstr("\"polygons\": " + std::to_string(c.cells)));
  EXPECT_THAT(r.out, HasSubstr("\"points\": " + std::to_string(c.points)));
  ASSERT_EQ(c.types.size(), std::size_t(c.cells));
  for (std::int64_t t : c.types) EXPECT_EQ(t, 7);  // VTK_POLYGON
  for (std::int64_t v : c.valid) EXPECT_EQ(v, 1);
  ASSERT_EQ(c.offsets.size(), std::size_t(c.cells));
  EXPECT_EQ(c.offsets.back(), std::int64_t(c.connectivity.size()));
  for (std::int64_t p : c.connectivity) EXPECT_LT(p, c.points);
  // ASCII holds the same mesh.
  const std::string ascii = (scratch() / "network_ascii.vtu").string();
  ASSERT_EQ(run_polydual("convert '" + msh + "' -o '" + ascii + "' --vtu-encoding ascii --quiet").code, 0);
  const VtuCounts a = read_vtu(ascii);
  EXPECT_EQ(a.connectivity, c.connectivity);
  EXPECT_EQ(a.valid, c.valid);
}

TEST(SurfaceConvert, SameBytesForAnyThreadCount) {
  if (!polydual::test::have_command("gmsh")) POLYDUAL_MISSING_TOOL("gmsh not found (package gmsh)");
  const std::string msh = gmsh_network();
  const std::string a = (scratch() / "t1.vtu").string(), b = (scratch() / "t2.vtu").string();
  ASSERT_EQ(run_polydual("convert '" + msh + "' -o '" + a + "' --threads 1 --quiet --zlib 6").code, 0);
  ASSERT_EQ(run_polydual("convert '" + msh + "' -o '" + b + "' --threads 2 --quiet --zlib 6").code, 0);
  EXPECT_EQ(slurp(a), slurp(b));
  EXPECT_EQ(read_vtu(a).valid.size(), read_vtu(b).valid.size());
}

TEST(SurfaceConvert, LatticeNetworkSummary) {
  const SurfaceConvertResult r = convert_surface(fracture_network_surface(8), {{4}, true});
  EXPECT_EQ(r.verdicts.invalid, 0u);
  EXPECT_EQ(r.areas.planar, 3u);
  EXPECT_LE(r.areas.max_rel_error, 1e-12);
  const Json j = surface_summary(r);
  EXPECT_THAT(j.dump(), HasSubstr("\"polygons\": " + std::to_string(r.dual.num_polygons())));
  ASSERT_EQ(r.report.stages.size(), 4u);
  EXPECT_EQ(r.report.stages[1].name, "dual");
  EXPECT_EQ(r.report.stages[2].name, "smooth");
  EXPECT_GE(r.smooth.min_quality_after, r.smooth.min_quality_before);
}

TEST(SurfaceConvert, RequireValidRefusesAnInvalidDualNamingItsPolygons) {
  // Three triangles around vertex 1, two of them obtuse at it (100 and 90
  // degrees apart from the 170-degree one): their centres are clamped onto
  // the far edges, and the fan triangle between the second and third centre
  // turns clockwise (about -9e-4 against +3e-3 for the others: far from zero).
  TetSoup soup;
  soup.source = "fan.msh";
  soup.points = {{0, 0, 0}, {0.1, 0, 0}, {-0.017365, 0.098481, 0}, {-0.196962, -0.034730, 0}};
  soup.triangles = {{{0, 1, 2}, 1}, {{0, 2, 3}, 1}, {{0, 3, 1}, 1}};
  SurfaceConvertParams off;
  off.smooth.sweeps = 0;
  off.split = false;
  const SurfaceConvertResult plain = convert_surface(soup, off);
  // Vertex 1's polygon, and those of vertices 3 and 4, whose fans hold the
  // clamped centres lying next to their far edges.
  ASSERT_EQ(plain.verdicts.invalid, 3u);
  EXPECT_EQ(invalid_polygon_items(plain, 2),
            (std::vector<std::string>{"polygon 0 (vertex 1, surface 1)", "polygon 2 (vertex 3, surface 1)"}));
  SurfaceConvertParams strict = off;
  strict.require_valid = true;
  try {
    convert_surface(soup, strict);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("fan.msh: 3 polygons are not star-shaped (--require-valid): polygon 0 (vertex 1"));
  }
  // Smoothing lowers the count of invalid polygons (the centres move within
  // their triangles' plane; no move makes a valid polygon invalid).
  SurfaceConvertParams smooth = off;
  smooth.smooth.sweeps = 8;
  EXPECT_LT(convert_surface(soup, smooth).verdicts.invalid, 3u);
  // The split (on by default) cuts the three vertices whole: one polygon per
  // triangle corner, all valid, the area kept; --require-valid then accepts.
  strict.split = true;
  const SurfaceConvertResult split = convert_surface(soup, strict);
  EXPECT_EQ(split.verdicts.invalid, 0u);
  EXPECT_EQ(split.dual.num_polygons(), 3u + 2u + 2u + 1u);  // corners of vertices 1, 3, 4; vertex 2 uncut
  EXPECT_LE(split.areas.max_rel_error, 1e-15);
  EXPECT_THAT(surface_summary(split).dump(), HasSubstr("\"whole_vertices\": 3"));
}

TEST(SurfaceConvert, DegenerateTriangleIsNamedAndNothingWritten) {
  const std::string msh = write("flat.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 2 0 0
4 0 1 0
$EndNodes
$Elements
2
1 2 2 1 1 1 2 4
2 2 2 1 1 1 2 3
$EndElements
)");
  const std::string out = (scratch() / "flat.vtu").string();
  const auto r = run_polydual("convert '" + msh + "' -o '" + out + "'");
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("flat.msh: triangle 2"));
  EXPECT_THAT(r.out, HasSubstr("degenerate"));
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(SurfaceConvert, FoamFormatIsAUsageError) {
  const std::string msh = write("square.msh", R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
2
1 2 2 1 1 1 2 3
2 2 2 1 1 1 3 4
$EndElements
)");
  const std::string out = (scratch() / "square_case").string();
  const auto r = run_polydual("convert '" + msh + "' -o '" + out + "' --format foam");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_THAT(r.out, HasSubstr("--format foam cannot hold the dual of a surface mesh"));
  EXPECT_FALSE(std::filesystem::exists(out));
  // The same mesh to VTU works: two right triangles (one shared centre),
  // four polygons, all valid.
  const auto ok = run_polydual("convert '" + msh + "' -o '" + out + ".vtu' --json --quiet");
  EXPECT_EQ(ok.code, 0) << ok.out;
  EXPECT_THAT(ok.out, HasSubstr("\"polygons\": 4"));
  EXPECT_THAT(ok.out, HasSubstr("\"points\": 9"));  // 1 centre, 4 midpoints, 4 corners
  EXPECT_THAT(ok.out, HasSubstr("\"invalid\": 0"));
}
