// Files written by meshio (Debian's python3-meshio under /usr/bin/python3),
// made at test time from the committed 5-tet cube (tests/data/cube5_v2.msh:
// regions = physical tags 10 / 20 with elementary tags 1 / 2, triangles with
// elementary tags 1..7): msh 2.2 ASCII and binary, msh 4.1 ASCII and binary,
// and Medit .mesh. Skipped when /usr/bin/python3 or meshio is missing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <unistd.h>

#include "classify/classify.h"
#include "core/error.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"
#include "require_tool.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;
const std::string kData = POLYDUAL_TEST_DATA;

// The meshio script: cells split into one block per elementary tag (as
// meshio's own Gmsh readers give them), since its msh 4.1 writer takes one
// entity per block; gmsh:dim_tags (required by that writer for several cell
// types) put every node, all cube corners, on a model point.
const char* const kScript = R"(
import sys, numpy as np, meshio
src, out = sys.argv[1], sys.argv[2]
m = meshio.read(src)
meshio.write(out + "/m22.msh", m, file_format="gmsh22", binary=False)
meshio.write(out + "/m22b.msh", m, file_format="gmsh22", binary=True)
cells, phys, geo, ref = [], [], [], []
for block, p, g in zip(m.cells, m.cell_data["gmsh:physical"], m.cell_data["gmsh:geometrical"]):
    for tag in sorted(set(g)):
        sel = g == tag
        cells.append(meshio.CellBlock(block.type, block.data[sel]))
        phys.append(p[sel]); geo.append(g[sel])
        ref.append(p[sel] if block.type == "tetra" else g[sel])
dim_tags = np.array([[0, i + 1] for i in range(len(m.points))])
m4 = meshio.Mesh(m.points, cells, point_data={"gmsh:dim_tags": dim_tags},
                 cell_data={"gmsh:physical": phys, "gmsh:geometrical": geo})
meshio.write(out + "/m41.msh", m4, file_format="gmsh", binary=False)
meshio.write(out + "/m41b.msh", m4, file_format="gmsh", binary=True)
keep = [i for i, c in enumerate(cells) if c.type != "vertex"]
medit = meshio.Mesh(m.points, [cells[i] for i in keep], cell_data={"medit:ref": [ref[i] for i in keep]})
meshio.write(out + "/m.mesh", medit)
)";

struct Scratch {
  fs::path path = fs::path(testing::TempDir()) / ("polydual_meshio_" + std::to_string(getpid()));
  bool ok = false;
  Scratch() {
    if (!test::have_python_module("meshio")) return;
    fs::create_directories(path);
    std::ofstream(path / "write.py") << kScript;
    const std::string cmd = "/usr/bin/python3 " + (path / "write.py").string() + " " + kData + "/cube5_v2.msh " +
                            path.string() + " > " + (path / "log").string() + " 2>&1";
    ok = std::system(cmd.c_str()) == 0;
    if (!ok) ADD_FAILURE() << "meshio script failed: " << cmd;
  }
  ~Scratch() { fs::remove_all(path); }
};
const Scratch& scratch() {
  static const Scratch s;
  return s;
}
#define REQUIRE_MESHIO() \
  if (scratch().path.empty() || !fs::exists(scratch().path / "m.mesh")) POLYDUAL_MISSING_TOOL("no /usr/bin/python3 with meshio (python3-meshio)")

std::map<std::int32_t, int> per_region(const TetSoup& s) {
  std::map<std::int32_t, int> n;
  for (std::int32_t r : s.tet_region) ++n[r];
  return n;
}
std::map<std::int32_t, int> per_face_tag(const TetSoup& s) {
  std::map<std::int32_t, int> n;
  for (const TaggedTriangle& t : s.triangles) ++n[t.tag];
  return n;
}
// Cube faces 1..6 (two triangles each) and the centre tet's faces 7.
const std::map<std::int32_t, int> kFaceTags = {{1, 2}, {2, 2}, {3, 2}, {4, 2}, {5, 2}, {6, 2}, {7, 4}};

// The model faces classify() finds on the original file.
std::size_t reference_faces();

std::size_t model_faces(const TetSoup& s) {
  try {
    return classify(s).model().count(2);
  } catch (const InputError& e) {
    ADD_FAILURE() << e.what();
    return 0;
  }
}

std::size_t reference_faces() {
  static const std::size_t n = model_faces(read_msh_file(kData + "/cube5_v2.msh"));
  return n;
}

TEST(IoMeshio, Msh22RegionsFromGmshPhysical) {
  REQUIRE_MESHIO();
  for (const char* name : {"m22.msh", "m22b.msh"}) {
    const TetSoup s = read_msh_file((scratch().path / name).string());
    EXPECT_EQ(per_region(s), (std::map<std::int32_t, int>{{10, 4}, {20, 1}})) << name;
    EXPECT_EQ(per_face_tag(s), kFaceTags) << name;  // physical 0: the elementary (gmsh:geometrical) tag
    EXPECT_EQ(model_faces(s), reference_faces()) << name;
  }
}

TEST(IoMeshio, Msh41RegionsFromGmshGeometrical) {
  REQUIRE_MESHIO();
  // meshio's msh 4.1 writer keeps one entity per block (gmsh:geometrical) and
  // declares in $Entities only the nodes' entities (here model points): the
  // blocks of the other dimensions are read by their entity tag.
  for (const char* name : {"m41.msh", "m41b.msh"}) {
    const TetSoup s = read_msh_file((scratch().path / name).string());
    EXPECT_EQ(per_region(s), (std::map<std::int32_t, int>{{1, 4}, {2, 1}})) << name;
    EXPECT_EQ(per_face_tag(s), kFaceTags) << name;
    EXPECT_FALSE(s.full_classification) << name;
    EXPECT_EQ(model_faces(s), reference_faces()) << name;
  }
}

TEST(IoMeshio, MeditRefs) {
  REQUIRE_MESHIO();
  const TetSoup s = read_medit_file((scratch().path / "m.mesh").string());
  EXPECT_EQ(per_region(s), (std::map<std::int32_t, int>{{10, 4}, {20, 1}}));
  EXPECT_EQ(per_face_tag(s), kFaceTags);
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(model_faces(s), reference_faces());
}

}  // namespace
}  // namespace polydual
