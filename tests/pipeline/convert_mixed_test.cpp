// `polydual convert` on mixed meshes (design §14): Gmsh meshes of hexahedra,
// prisms, pyramids and tets made at test time, converted by the command with
// --require-valid (exit 0: closed cells, sound faces, the material volumes of
// planar boxes, every cell star-shaped by the exact test); the library entry
// records the input's cell types and the split (no round when the optimised
// dual is valid); a non-conformal input
// is an error naming the place.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "pipeline/convert.h"
#include "pipeline/summary.h"
#include "require_tool.h"
#include "run_command.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::run_polydual;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("polydual_mixed_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
  std::string file(const std::string& name, const std::string& text = "") const {
    const std::string p = (path / name).string();
    if (!text.empty()) std::ofstream(p) << text;
    return p;
  }
};

// gmsh -3 on `geo`; the .msh path, or "" when gmsh failed.
std::string gmsh_mesh(const TempDir& d, const std::string& name, const std::string& geo) {
  const std::string g = d.file(name + ".geo", geo), m = d.file(name + ".msh");
  const int rc = std::system(("gmsh -3 '" + g + "' -o '" + m + "' > /dev/null 2>&1").c_str());
  return rc == 0 ? m : "";
}

constexpr const char* kSquare =
    "Point(1) = {0,0,0,0.25}; Point(2) = {1,0,0,0.25}; Point(3) = {1,1,0,0.25}; Point(4) = {0,1,0,0.25};\n"
    "Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};\n"
    "Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};\n";

// A box extruded in 4 layers of hexahedra; a prism layer under a tet block;
// a transfinite hex block joined to tets (Gmsh puts pyramids between).
const std::pair<const char*, std::string> kMeshes[] = {
    {"hexes", std::string(kSquare) + "Transfinite Curve{1,2,3,4} = 5; Transfinite Surface{1}; Recombine Surface{1};\n"
                                     "Extrude {0,0,1} { Surface{1}; Layers{4}; Recombine; }\n"},
    {"prisms", std::string(kSquare) + "out[] = Extrude {0,0,0.2} { Surface{1}; Layers{2}; Recombine; };\n"
                                      "Extrude {0,0,0.8} { Surface{out[0]}; }\n"},
    {"pyramids", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0,0,0, 1,1,0.5};\nBox(2) = {0,0,0.5, 1,1,0.5};\n"
                 "Coherence;\nTransfinite Curve{:} = 4;\nTransfinite Surface{:} = {};\nRecombine Surface{:};\n"
                 "Transfinite Volume{1};\nRecombine Volume{1};\n"},
};

TEST(ConvertMixed, GmshMixedMeshesConvertValidAndClosed) {
  if (!test::have_command("gmsh")) POLYDUAL_MISSING_TOOL("gmsh is not installed (package gmsh)");
  const TempDir d;
  for (const auto& [name, geo] : kMeshes) {
    const std::string msh = gmsh_mesh(d, name, geo);
    ASSERT_FALSE(msh.empty()) << name << ": gmsh failed";
    for (const char* format : {"vtu", "foam"}) {
      const std::string out = d.file(std::string(name) + (std::string(format) == "vtu" ? ".vtu" : "_foam"));
      const auto r = run_polydual("convert '" + msh + "' -o '" + out + "' --format " + format + " --require-valid");
      EXPECT_EQ(r.code, 0) << name << " " << format << ": " << r.out;
      EXPECT_THAT(r.out, HasSubstr("  mixed mesh (\"")) << name;
      EXPECT_THAT(r.out, HasSubstr(", after 0;")) << name;
      EXPECT_TRUE(fs::exists(out)) << name;
    }
  }
}

TEST(ConvertMixed, SummaryRecordsTheCellTypesAndTheSplit) {
  if (!test::have_command("gmsh")) POLYDUAL_MISSING_TOOL("gmsh is not installed (package gmsh)");
  const TempDir d;
  const std::string msh = gmsh_mesh(d, "pyramids", kMeshes[2].second);
  ASSERT_FALSE(msh.empty());
  const ConvertResult r = convert_file(msh, d.file("p.vtu"), PolyFormat::Vtu, PipelineParams{});
  ASSERT_TRUE(r.mixed.has_value());
  EXPECT_GT(r.mixed->cell_counts[std::size_t(CellType::Pyramid)], 0u);
  EXPECT_GT(r.mixed->cell_counts[std::size_t(CellType::Hex)], 0u);
  EXPECT_EQ(r.check.validation.closed_cells, r.mesh.num_cells());
  EXPECT_TRUE(r.check.validation.ok());
  EXPECT_TRUE(r.check.validation.geometry_ok());
  EXPECT_EQ(r.check.validation.volume_checked_materials.size(), 2u);  // both boxes are planar
  EXPECT_EQ(r.report.invalid_after, 0u);
  for (const char* stage : {"read", "classify", "dual", "cleanup", "cells", "check", "optimize", "check_after", "write"})
    EXPECT_NE(r.report.stage(stage), nullptr) << stage;
  ASSERT_NE(r.report.stage("split"), nullptr);
  EXPECT_THAT(r.report.stage("split")->stats.dump(0), HasSubstr("\"rounds\":0"));  // valid once optimised
  const Json j = convert_summary(r, PipelineParams{});
  EXPECT_THAT(j.dump(0), HasSubstr("\"mixed\":true"));
  EXPECT_THAT(j.dump(0), HasSubstr("\"pyramids\":"));
}

// A Gmsh 2.2 file that names its volumes only: build_primal infers one model
// face per region pair; the pipeline cuts them at the box's 90-degree edges
// (classify/primal_features.h), so the caps keep the corners and both
// materials keep their volume (without the cut: 17 % and 6 % lost).
TEST(ConvertMixed, InferredModelFacesAreCutAtFeatureEdges) {
  if (!test::have_command("gmsh")) POLYDUAL_MISSING_TOOL("gmsh is not installed (package gmsh)");
  const TempDir d;
  const std::string geo = std::string(kSquare) +
                          "Transfinite Curve{1,2,3,4}=4;Transfinite Surface{1};Recombine Surface{1};\n"
                          "out[] = Extrude {0,0,0.5} { Surface{1}; Layers{2}; Recombine; };\n"
                          "out2[] = Extrude {0,0,0.5} { Surface{out[0]}; };\n"
                          "Physical Volume(\"hexes\") = {out[1]};\nPhysical Volume(\"tets\") = {out2[1]};\n";
  const std::string g = d.file("physical.geo", geo), msh = d.file("physical.msh");
  ASSERT_EQ(std::system(("gmsh -3 '" + g + "' -format msh22 -o '" + msh + "' > /dev/null 2>&1").c_str()), 0);
  const ConvertResult r = convert_file(msh, d.file("p.vtu"), PolyFormat::Vtu, PipelineParams{});
  ASSERT_TRUE(r.mixed.has_value());
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  EXPECT_EQ(r.check.validation.volume_checked_materials.size(), 2u);
  EXPECT_TRUE(r.check.validation.geometry_ok());
  for (const auto& [tag, v] : r.check.validation.material_volume) EXPECT_NEAR(v, 0.5, 1e-12) << "material " << tag;
  // The box's 8 corners and 12 edges, and the interface's rim, are model entities.
  std::size_t corners = 0;
  for (std::size_t v = 0; v < r.mixed->mesh.num_vertices(); ++v) corners += r.mixed->mesh.vertex_class(VertexId(v)).dim == 0;
  EXPECT_GE(corners, 8u);
}

// A hexahedron whose bottom quadrangle (1 2 3 4) meets two tets on its
// triangles (1 2 3) and (1 3 4): non-conformal.
TEST(ConvertMixed, QuadrangleAgainstTwoTrianglesIsAnErrorNamingThePlace) {
  const TempDir d;
  const std::string msh = d.file("nonconformal.msh",
                                 "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n9\n"
                                 "1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n9 0.5 0.5 -1\n"
                                 "$EndNodes\n$Elements\n3\n"
                                 "1 5 2 1 1 1 2 3 4 5 6 7 8\n2 4 2 1 1 1 3 2 9\n3 4 2 1 1 1 4 3 9\n$EndElements\n");
  const auto r = run_polydual("convert '" + msh + "' -o '" + d.file("n.vtu") + "'");
  EXPECT_NE(r.code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("nonconformal.msh"));
  EXPECT_THAT(r.out, HasSubstr("hexahedron 1"));
  EXPECT_THAT(r.out, HasSubstr("non-conformal mesh: quadrangle face"));
  EXPECT_THAT(r.out, HasSubstr("tetrahedron 1"));
  EXPECT_FALSE(fs::exists(d.path / "n.vtu"));
}

}  // namespace
}  // namespace polydual
