// Nothing broken is certified, end to end through the command: `check`
// refuses a VTU whose Cells arrays disagree and exits 1 on a mesh that is
// not sound, naming the check and the cells; `convert` and `optimize` warn
// about a result with defects (and write it), and refuse it with
// --require-valid (nothing written); `optimize --primal` refuses a tet mesh
// that is not the polyhedral mesh's.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "classify/classify.h"
#include "dual/build_dual.h"
#include "generate/domains.h"
#include "io/vtu_poly_writer.h"
#include "run_command.h"
#include "vtu_text_edit.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using namespace polydual;

namespace {

struct ScratchRoot {
  fs::path path = fs::temp_directory_path() / ("polydual_check_defects_" + std::to_string(::getpid()));
  ScratchRoot() { fs::create_directories(path); }
  ~ScratchRoot() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};
fs::path scratch(const std::string& name) {
  static const ScratchRoot root;
  return root.path / name;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct CmdResult {
  int code;
  std::string out, err;
};
CmdResult run(const std::string& args) {
  static int counter = 0;
  const fs::path err = scratch("stderr_" + std::to_string(counter++));
  CmdResult r{0, {}, {}};
  r.out = polydual::testing::capture(std::string(POLYDUAL_BINARY) + " " + args + " 2>" + err.string(), r.code);
  r.err = slurp(err);
  return r;
}

// A cube tet mesh (Medit, written by the command) and its dual in ASCII VTU.
struct CubeFiles {
  fs::path mesh, vtu;
};
const CubeFiles& cube_files() {
  static const CubeFiles f = [] {
    CubeFiles c{scratch("cube.mesh"), scratch("cube.vtu")};
    EXPECT_EQ(run("generate cube --tets 2000 -o " + c.mesh.string() + " --quiet").code, 0);
    EXPECT_EQ(run("convert " + c.mesh.string() + " -o " + c.vtu.string() + " --vtu-encoding ascii --quiet").code, 0);
    return c;
  }();
  return f;
}

using polydual::testing::with_array;

// The Medit file with vertex `v` (1-based) duplicated at the end and the
// first tet that uses it given the copy: a crack along that tet's faces.
std::string cracked_medit(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::size_t vi = 0, ti = 0;
  while (lines[vi] != "Vertices") ++vi;
  while (lines[ti] != "Tetrahedra") ++ti;
  const int nv = std::stoi(lines[vi + 1]);
  std::istringstream tet(lines[ti + 2]);
  std::vector<std::string> ids(5);
  for (std::string& id : ids) tet >> id;
  const std::string v = ids[0];
  ids[0] = std::to_string(nv + 1);  // the copy
  lines[ti + 2] = ids[0] + " " + ids[1] + " " + ids[2] + " " + ids[3] + " " + ids[4];
  const std::string copy = lines[vi + 1 + std::stoi(v)];
  lines[vi + 1] = std::to_string(nv + 1);
  lines.insert(lines.begin() + static_cast<long>(vi) + 2 + nv, copy);
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

// The cube's dual with one half-face taken out of cell 7's list (its
// neighbour still lists the face): cell 7 is open, the face a boundary face
// classified interior.
fs::path dual_with_a_removed_face() {
  const fs::path p = scratch("removed_face.vtu");
  if (fs::exists(p)) return p;
  const ClassifiedTetMesh primal = classify(generate_domain(Domain::Cube, 1500));
  PolyMesh pm = build_dual(primal);
  const CellId c(7u);
  std::vector<HalfFace> faces;
  std::vector<std::uint32_t> offsets{0};
  for (std::size_t k = 0; k < pm.num_cells(); ++k) {
    const auto cell = pm.cell(CellId(static_cast<std::uint32_t>(k)));
    for (std::size_t i = 0; i < cell.size(); ++i)
      if (!(k == c.idx && i == 0)) faces.push_back(cell[i]);
    offsets.push_back(static_cast<std::uint32_t>(faces.size()));
  }
  pm.cell_faces = faces;
  pm.cell_offsets = offsets;
  write_vtu_poly(pm, p.string());
  return p;
}

}  // namespace

TEST(CheckDefects, SoundOutputPassesCheck) {
  const CmdResult r = run("check " + cube_files().vtu.string() + " --json");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_THAT(r.out, HasSubstr("\"topology_ok\": true"));
  EXPECT_THAT(r.out, HasSubstr("\"defects\": []"));
}

// Each Cells array corrupted: refused with a message naming the file, the
// array and the cell, exit 1 (never a crash, never topology_ok).
TEST(CheckDefects, CheckRefusesEveryCorruptedCellsArray) {
  const std::string s = slurp(cube_files().vtu);
  using V = std::vector<std::string>;
  struct Case {
    const char* name;
    const char* array;
    std::function<void(V&)> edit;
    const char* expect;
  };
  const Case cases[] = {
      {"negative_id", "connectivity", [](V& v) { v[0] = "-7"; }, "cell 0: DataArray 'connectivity': point id -7"},
      {"huge_offset", "offsets", [](V& v) { v[0] = "1000000000"; }, "cell 0: DataArray 'offsets': value 1000000000"},
      {"decreasing", "offsets", [](V& v) { v[1] = std::to_string(std::stol(v[0]) - 1); },
       "cell 1: DataArray 'offsets': value"},
      {"wrong_type", "types", [](V& v) { v[3] = "12"; }, "cell 3: DataArray 'types': type 12 is not a VTK_POLYHEDRON"},
      {"truncated_faces", "faces", [](V& v) { v.resize(v.size() - 2); }, "DataArray 'faces': face"},
      {"faceoffsets", "faceoffsets", [](V& v) { v[0] = std::to_string(std::stol(v[0]) + 1); },
       "cell 0: DataArray 'faceoffsets'"},
  };
  for (const Case& c : cases) {
    const fs::path p = scratch(std::string("corrupt_") + c.name + ".vtu");
    std::ofstream(p) << with_array(s, c.array, c.edit);
    const CmdResult r = run("check " + p.string());
    EXPECT_EQ(r.code, 1) << c.name << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(p.string() + ": ")) << c.name;
    EXPECT_THAT(r.err, HasSubstr(c.expect)) << c.name;
    EXPECT_THAT(r.out, Not(HasSubstr("topology_ok"))) << c.name;
  }
}

TEST(CheckDefects, CheckFailsOnADualWithARemovedFace) {
  const CmdResult r = run("check " + dual_with_a_removed_face().string() + " --json");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_THAT(r.out, HasSubstr("\"topology_ok\": false"));
  EXPECT_THAT(r.out, HasSubstr("\"check\": \"open_cells\""));
  EXPECT_THAT(r.err, HasSubstr("polydual check: error: " + dual_with_a_removed_face().string() + ": not a sound mesh"));
  EXPECT_THAT(r.err, HasSubstr("open_cells: 1 cells not closed"));
  EXPECT_THAT(r.err, HasSubstr(": cell 7\n"));
  EXPECT_THAT(r.err, HasSubstr("face_errors: "));  // the face its neighbour lists is interior without a neighbour
}

// The reported case: a Medit mesh where one tet uses a duplicated vertex (a
// crack) is refused when it is read (classify/self_overlap.h), nothing written.
TEST(CheckDefects, ConvertRefusesACrackedMesh) {
  const fs::path in = scratch("cracked.mesh"), out = scratch("cracked.vtu");
  std::ofstream(in) << cracked_medit(slurp(cube_files().mesh));
  for (const char* extra : {"", " --require-valid"}) {
    const CmdResult r = run("convert " + in.string() + " -o " + out.string() + extra);
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr(in.string() + ": vertex "));
    EXPECT_THAT(r.err, HasSubstr("are at the same position"));
    EXPECT_FALSE(fs::exists(out));
  }
}

// The poles of a Gmsh sphere are model vertices at the end of the seam curve
// inside the sphere's face: the cap round each winds through the seam's
// midpoint and is split through the pole's dual point (build_dual.cpp
// add_cap), so the dual is sound: no warning, accepted by --require-valid
// (before, "missing_model_entities: model vertex 1, model vertex 2").
TEST(CheckDefects, ASpheresPolesAreOnTheDual) {
  const std::string in = std::string(POLYDUAL_TEST_DATA) + "/gmsh/sphere_coarse.msh";
  const fs::path out = scratch("sphere.vtu");
  for (const char* opt : {"", " --optimize none"}) {
    fs::remove(out);
    const CmdResult r = run("convert " + in + " -o " + out.string() + " --json --require-valid" + opt);
    EXPECT_EQ(r.code, 0) << opt << r.err;
    EXPECT_THAT(r.out, HasSubstr("\"topology_ok\": true")) << opt;
    EXPECT_THAT(r.out, HasSubstr("\"missing_model_entities\": []")) << opt;
    EXPECT_THAT(r.err, Not(HasSubstr("not sound"))) << opt;
    EXPECT_EQ(run("check " + out.string()).code, 0) << opt;
  }
}

TEST(CheckDefects, OptimizeWarnsOnADefectiveMeshAndRequireValidRefuses) {
  const fs::path in = dual_with_a_removed_face(), out = scratch("opt_broken.vtu"), refused = scratch("opt_refused.vtu");
  const CmdResult w = run("optimize " + in.string() + " -o " + out.string() + " --optimize untangle --json");
  EXPECT_EQ(w.code, 0) << w.err;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_THAT(w.out, HasSubstr("\"check\": \"open_cells\""));
  EXPECT_THAT(w.err, HasSubstr("polydual optimize: warning: " + out.string() + " written, but the mesh is not sound"));
  EXPECT_THAT(w.err, HasSubstr(": cell 7\n"));
  const CmdResult r = run("optimize " + in.string() + " -o " + refused.string() + " --optimize untangle --require-valid");
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr(in.string() + ": the mesh is not sound: open_cells: 1 cells not closed"));
  EXPECT_FALSE(fs::exists(refused));
}

// optimize --primal with the mesh's own primal is accepted; any other tet
// mesh (another mesh, the same one scaled, one corner moved by 1e-12) is
// refused naming both files, nothing written.
TEST(CheckDefects, OptimizeRefusesAPrimalThatIsNotTheMeshs) {
  const std::string vtu = cube_files().vtu.string(), out = scratch("opt_primal.vtu").string();
  const CmdResult ok = run("optimize " + vtu + " --primal " + cube_files().mesh.string() + " -o " + out +
                           " --optimize untangle");
  EXPECT_EQ(ok.code, 0) << ok.err;
  fs::remove(out);
  const std::string text = slurp(cube_files().mesh);
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::size_t vi = 0;
  while (lines[vi] != "Vertices") ++vi;
  const int nv = std::stoi(lines[vi + 1]);
  auto write = [&](const std::string& name, const std::function<std::string(int, double, double, double, const std::string&)>& f) {
    std::string s;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const int k = static_cast<int>(i) - static_cast<int>(vi) - 2;
      if (k >= 0 && k < nv) {
        std::istringstream v(lines[i]);
        double x, y, z;
        std::string ref;
        v >> x >> y >> z >> ref;
        s += f(k, x, y, z, ref) + "\n";
      } else {
        s += lines[i] + "\n";
      }
    }
    const fs::path p = scratch(name);
    std::ofstream(p) << s;
    return p.string();
  };
  auto fmt = [](double x, double y, double z, const std::string& ref) {
    std::ostringstream o;
    o.precision(17);
    o << x << " " << y << " " << z << " " << ref;
    return o.str();
  };
  const fs::path other = scratch("other.mesh");
  ASSERT_EQ(run("generate cube --tets 3000 -o " + other.string() + " --quiet").code, 0);
  const std::string scaled = write("scaled.mesh", [&](int, double x, double y, double z, const std::string& r) {
    return fmt(1.5 * x, 1.5 * y, 1.5 * z, r);
  });
  bool moved = false;  // the first corner of the cube, moved inwards by 1e-12 along x
  const std::string nudged = write("nudged.mesh", [&](int, double x, double y, double z, const std::string& r) {
    const bool corner = !moved && (x == 0 || x == 1) && (y == 0 || y == 1) && (z == 0 || z == 1);
    moved = moved || corner;
    return fmt(corner ? (x == 0 ? 1e-12 : 1 - 1e-12) : x, y, z, r);
  });
  ASSERT_TRUE(moved);
  const std::pair<std::string, std::string> cases[] = {
      {other.string(), "its vertex 480 (0-based) has no cell in " + vtu},  // more vertices
      {scaled, "is far from its cell"},
      {nudged, "lies on a model vertex, but no cell holding it has its primal vertex there"},
  };
  for (const auto& [primal, expect] : cases) {
    const CmdResult r = run("optimize " + vtu + " --primal " + primal + " -o " + out + " --optimize untangle");
    EXPECT_EQ(r.code, 1) << primal;
    EXPECT_THAT(r.err, HasSubstr("polydual optimize: error: " + primal + ": is not the tet mesh " + vtu +
                                 " is the dual of: "));
    EXPECT_THAT(r.err, HasSubstr(expect));
    EXPECT_FALSE(fs::exists(out)) << primal;
  }
}
