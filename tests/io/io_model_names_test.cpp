// Model names through the writers: Gmsh physical names (msh 2.2 and 4.1) name
// OpenFOAM patches, cell zones and face zones (sanitised, unique, one per
// name) and appear as VTU field data; a mesh without names is written as
// before names existed ("face_<tag>", "material_<tag>", no name arrays).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>

#include "require_tool.h"
#include "classify/classify.h"
#include "io/foam_writer.h"
#include "io/read_tet_mesh.h"
#include "io/vtu_poly_reader.h"
#include "io/write_poly_mesh.h"
#include "pipeline/convert.h"
#include "scratch_dir.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;
using testing::Not;

bool have(const char* tool) { return test::have_command(tool); }

fs::path scratch() { return test::scratch_dir(); }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// A unit box with a spherical inclusion: the inclusion is Physical Volume
// "steel", the rest the unnamed Physical Volume(7); the face x = 0 is
// "inlet face" (a name OpenFOAM cannot take as it is), the other five "wall".
// `named` false: the same model without physical groups.
const char* kGeo = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Sphere(2) = {0.5, 0.5, 0.5, 0.25};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.CharacteristicLengthMax = 0.25;
)";
const char* kGroups = R"(steel() = Volume In BoundingBox{0.2, 0.2, 0.2, 0.8, 0.8, 0.8};
matrix() = Volume{:};
matrix() -= steel();
inlet() = Surface In BoundingBox{-0.01, -0.01, -0.01, 0.01, 1.01, 1.01};
wall() = Surface In BoundingBox{-0.01, -0.01, -0.01, 1.01, 1.01, 1.01};
wall() -= Surface In BoundingBox{0.2, 0.2, 0.2, 0.8, 0.8, 0.8};
wall() -= inlet();
Physical Volume("steel") = {steel()};
Physical Volume(7) = {matrix()};
Physical Surface("wall") = {wall()};
Physical Surface("inlet face") = {inlet()};
)";

std::string gmsh_model(const fs::path& dir, const std::string& format, bool named, const std::string& extra = "") {
  const fs::path geo = dir / (std::string(named ? "named" : "plain") + ".geo");
  std::ofstream(geo) << kGeo << (named ? kGroups : "") << extra;
  const std::string msh = (dir / (geo.stem().string() + "_" + format + ".msh")).string();
  const std::string cmd = "gmsh -3 '" + geo.string() + "' -format " + format + " -o '" + msh + "' > /dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return msh;
}

PipelineParams fast_params() {
  PipelineParams p;
  p.optim.method = OptimParams::Method::None;
  return p;
}

// The names listed in an OpenFOAM list file (boundary, cellZones, faceZones):
// after the list's "(", each word on a line followed by a line "{".
std::set<std::string> entries(const fs::path& file) {
  std::istringstream in(slurp(file));
  std::set<std::string> names;
  std::string line, prev;
  while (std::getline(in, line) && line != "(") {}
  while (std::getline(in, line)) {
    if (line.find_first_not_of(' ') != std::string::npos && line.substr(line.find_first_not_of(' ')) == "{") {
      const auto a = prev.find_first_not_of(' ');
      names.insert(prev.substr(a));
    }
    prev = line;
  }
  return names;
}

class ModelNamesThroughMsh : public testing::TestWithParam<const char*> {};

TEST_P(ModelNamesThroughMsh, NamePatchesAndZones) {
  if (!have("gmsh")) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  const fs::path dir = scratch() / GetParam();
  fs::create_directories(dir);
  const std::string msh = gmsh_model(dir, GetParam(), true);
  // The default pipeline (optimised): checkMesh below also checks geometry.
  const ConvertResult r = convert_file(msh, (dir / "case").string(), PolyFormat::Foam, PipelineParams{});
  const fs::path poly = dir / "case" / "constant" / "polyMesh";
  // Five model faces of "wall" are one patch; "inlet face" is sanitised.
  EXPECT_EQ(entries(poly / "boundary"), (std::set<std::string>{"wall", "inlet_face"}));
  EXPECT_EQ(entries(poly / "cellZones"), (std::set<std::string>{"steel", "material_7"}));
  // The sphere, in no physical group, is an unnamed interface.
  const std::set<std::string> zones = entries(poly / "faceZones");
  ASSERT_EQ(zones.size(), 1u);
  EXPECT_EQ(zones.begin()->rfind("interface_", 0), 0u) << *zones.begin();
  EXPECT_THAT(r.written.dump(0), HasSubstr("\"patches\":2"));

  // The VTU carries the names as field data, and is still read back.
  const ConvertResult v = convert_file(msh, (dir / "m.vtu").string(), PolyFormat::Vtu, fast_params());
  const std::string vtu = slurp(dir / "m.vtu");
  EXPECT_THAT(vtu, HasSubstr("type=\"String\" Name=\"region_name\" NumberOfTuples=\"1\""));
  EXPECT_THAT(vtu, HasSubstr("type=\"String\" Name=\"face_name\" NumberOfTuples=\"6\""));
  EXPECT_THAT(vtu, HasSubstr(std::string("steel\0", 6)));
  EXPECT_THAT(vtu, HasSubstr(std::string("inlet face\0", 11)));
  EXPECT_EQ(read_vtu_poly((dir / "m.vtu").string()).num_cells(), v.mesh.num_cells());

  // OpenFOAM's checker reads the named case.
  if (!fs::exists("/usr/bin/checkMesh") || !fs::exists("/usr/share/openfoam/etc/controlDict")) return;
  const fs::path log = dir / "checkMesh.log";
  const std::string cmd = "export WM_PROJECT_DIR=/usr/share/openfoam; /usr/bin/checkMesh -case '" +
                          (dir / "case").string() + "' > '" + log.string() + "' 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(log);
  const std::string out = slurp(log);
  EXPECT_THAT(out, HasSubstr("Mesh OK.")) << out;
  EXPECT_THAT(out, testing::ContainsRegex("\n *wall +[0-9]+ +[0-9]+")) << out;
  EXPECT_THAT(out, testing::ContainsRegex("\n *inlet_face +[0-9]+ +[0-9]+")) << out;
}

INSTANTIATE_TEST_SUITE_P(Gmsh, ModelNamesThroughMsh, testing::Values("msh22", "msh41"));

// Without names the case is what the writer always wrote: face_<tag> patches,
// material_<tag> zones, and the same bytes as a write with no names at all;
// the VTU has no name arrays.
TEST(ModelNames, MeshWithoutNamesIsUnchanged) {
  if (!have("gmsh")) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  const fs::path dir = scratch() / "plain";
  fs::create_directories(dir);
  const std::string msh = gmsh_model(dir, "msh41", false);
  const ConvertResult r = convert_file(msh, (dir / "case").string(), PolyFormat::Foam, fast_params());
  write_foam(r.mesh, (dir / "bare").string());
  for (const char* f : {"points", "faces", "owner", "neighbour", "boundary", "cellZones", "faceZones"})
    EXPECT_EQ(slurp(dir / "case/constant/polyMesh" / f), slurp(dir / "bare/constant/polyMesh" / f)) << f;
  for (const std::string& p : entries(dir / "case/constant/polyMesh/boundary")) EXPECT_EQ(p.rfind("face_", 0), 0u) << p;
  for (const std::string& z : entries(dir / "case/constant/polyMesh/cellZones")) EXPECT_EQ(z.rfind("material_", 0), 0u) << z;
  convert_file(msh, (dir / "m.vtu").string(), PolyFormat::Vtu, fast_params());
  EXPECT_THAT(slurp(dir / "m.vtu"), Not(HasSubstr("_name")));
}

// Names OpenFOAM cannot take are sanitised and kept apart: "a b" and "a;b"
// both become "a_b" (the second "a_b_2"), "2nd" "_2nd", "x/y" "x_y"; two
// faces of one name share a patch.
TEST(ModelNames, SanitisedUniqueWords) {
  if (!have("gmsh")) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  const fs::path dir = scratch() / "words";
  fs::create_directories(dir);
  const ConvertResult r = convert_file(gmsh_model(dir, "msh41", false), (dir / "m.vtu").string(), PolyFormat::Vtu,
                                       fast_params());
  std::set<std::int32_t> faces;
  for (std::size_t f = 0; f < r.mesh.num_faces(); ++f)
    if (r.mesh.face_kind[f] == FaceKind::External) faces.insert(r.mesh.face_tag[f]);
  ASSERT_GE(faces.size(), 6u);
  std::vector<std::int32_t> tags(faces.begin(), faces.end());
  ModelNames names;
  names.faces = {{tags[0], "a b"}, {tags[1], "a;b"}, {tags[2], "2nd"}, {tags[3], "2nd"}};
  names.regions = {{r.mesh.cell_material.front(), "x/y"}};
  const FoamReport rep = write_foam(r.mesh, (dir / "case").string(), {}, names);
  const std::set<std::string> patches = entries(dir / "case/constant/polyMesh/boundary");
  EXPECT_TRUE(patches.count("a_b") && patches.count("a_b_2") && patches.count("_2nd")) << testing::PrintToString(patches);
  EXPECT_EQ(rep.patches, faces.size() - 1);  // tags[2] and tags[3] share "_2nd"
  EXPECT_TRUE(entries(dir / "case/constant/polyMesh/cellZones").count("x_y"));
}

// A volume in two physical groups (msh 4.1 lists both tags on the entity):
// its model region carries both groups' tags, and the first name.
TEST(ModelNames, EntityCarriesAllItsPhysicalGroups) {
  if (!have("gmsh")) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  const fs::path dir = scratch() / "two_groups";
  fs::create_directories(dir);
  const TetSoup soup = read_tet_mesh(gmsh_model(dir, "msh41", true, "Physical Volume(\"hard\") = {steel()};\n"));
  std::map<std::string, std::int32_t> tag_of;
  for (const NamedGroup& g : soup.groups)
    if (g.dim == 3) tag_of[g.name] = g.tag;
  ASSERT_TRUE(tag_of.count("steel") && tag_of.count("hard"));
  const ClassifiedTetMesh m = classify(soup);
  std::size_t seen = 0;
  for (const ModelEntity& r : m.model().entities[3]) {
    if (r.name == "steel") {
      ++seen;
      std::vector<std::int32_t> both{tag_of["steel"], tag_of["hard"]};
      std::sort(both.begin(), both.end());
      EXPECT_EQ(r.groups, both);
    } else {
      EXPECT_EQ(r.groups, (std::vector<std::int32_t>{7}));  // the unnamed Physical Volume(7)
    }
  }
  EXPECT_EQ(seen, 1u);
  for (const ModelEntity& f : m.model().entities[2])
    if (f.name == "wall") EXPECT_EQ(f.groups.size(), 1u);
}

}  // namespace
}  // namespace polydual
