// The split loop's last fallback (proofs/split.md, T1): whatever the budget
// of optimised rounds, the closure cuts whole the vertices of the cells still
// invalid, every pinned point at its barycentre, until every invalid cell is
// a whole vertex's barycentric corner (convex, proofs/dual_cuts.md C5); so
// the split ends with 0 invalid cells. Checked on a TetGen mesh with slivers
// and sharp corners made at test time (Gmsh OpenCASCADE wedge + cone ->
// STL -> `tetgen -pY`: the loop without the closure ran out of rounds with
// 3 to 7 invalid cells on it, budgets 1 to 3), on random classified meshes,
// and the command's warning when cells stay invalid (`--no-split`).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "generate/random_mesh.h"
#include "io/read_tet_mesh.h"
#include "pipeline/convert.h"
#include "require_tool.h"
#include "run_command.h"
#include "scratch_dir.h"

namespace polydual {
namespace {

// A thin wedge (10:1.2) with a cone standing on it, meshed by Gmsh's STL and
// TetGen without a quality bound: slivers at the wedge's sharp edge and the
// cone's tip. Returns the .ele path, empty if a tool is missing or failed.
std::string wedge_cone_mesh() {
  static const std::string path = [] {
    if (!test::have_command("gmsh") || !test::have_command("tetgen"))
      return std::string();
    const std::filesystem::path dir = test::scratch_dir("wedge_cone");
    std::ofstream(dir / "w.geo") << "SetFactory(\"OpenCASCADE\");\n"
                                    "Point(1)={0,0,0}; Point(2)={1,0,0}; Point(3)={1,0.12,0};\n"
                                    "Line(1)={1,2}; Line(2)={2,3}; Line(3)={3,1}; Curve Loop(1)={1,2,3};\n"
                                    "Plane Surface(1)={1};\n"
                                    "Extrude{0,0,0.4}{Surface{1};}\n"
                                    "Cone(5) = {0.5,0.06,0.4, 0,0,0.3, 0.12,0};\n"
                                    "BooleanUnion(6) = { Volume{1}; Delete; }{ Volume{5}; Delete; };\n"
                                    "Mesh.MeshSizeMax = 0.1;\n";
    const std::string d = dir.string();
    const std::string cmd = "cd '" + d + "' && gmsh -2 -format stl w.geo -o w.stl > /dev/null 2>&1 && " +
                            "tetgen -pYQ w.stl > /dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) return std::string();
    return d + "/w.1.ele";
  }();
  return path;
}

const Json* split_stat(const ConvertResult& r, const char* key) {
  const StageRecord* s = r.report.stage("split");
  return s ? s->stats.find(key) : nullptr;
}

TEST(SplitClosure, TetgenSliversEndValidWithAnyBudget) {
  const std::string ele = wedge_cone_mesh();
  if (ele.empty()) POLYDUAL_MISSING_TOOL("gmsh or tetgen is not installed (or failed)");
  const TetSoup soup = read_tet_mesh(ele);
  PipelineParams plain;
  plain.optim.method = OptimParams::Method::None;
  plain.split.enabled = false;
  const ConvertResult unsplit = convert(soup, plain);
  ASSERT_GT(unsplit.report.invalid_after, 0u);  // the mesh needs the split
  for (const OptimParams::Method method : {OptimParams::Method::None, OptimParams::Method::Local})
    for (const int budget : {1, 3}) {
      PipelineParams p;
      p.optim.method = method;
      p.split.max_rounds = budget;
      const ConvertResult r = convert(soup, p);
      const std::string what = std::string(method_name(method)) + ", budget " + std::to_string(budget);
      EXPECT_EQ(r.check.invalid_cells, 0u) << what;
      EXPECT_EQ(r.report.invalid_after, 0u) << what;
      EXPECT_TRUE(r.check.validation.ok()) << what;
      // With one round the budget alone does not end it: the closure does.
      const Json* closure = split_stat(r, "closure_rounds");
      ASSERT_NE(closure, nullptr);
      if (budget == 1 && method == OptimParams::Method::None) EXPECT_GT(std::stoi(closure->dump(0)), 0) << what;
    }
}

// The property on random classified meshes (every generator family: slivers
// of random Delaunay meshes, cospherical lattice points, notches, sheets):
// with a budget of one round the closure ends every one of them valid, with
// and without the untangler in the rounds.
TEST(SplitClosure, RandomMeshesEndValidWithOneRound) {
  const char* env = std::getenv("POLYDUAL_SPLIT_MESHES");
  const int count = env ? std::atoi(env) / 4 : 120;
  std::size_t closed_by_closure = 0;
  for (int i = 0; i < count; ++i) {
    RandomMeshParams mp;
    mp.seed = std::uint64_t(1000 + i);
    mp.num_points = 20 + (i % 7) * 8;
    mp.notch = i % 2 == 0;
    mp.lattice_points = i % 3 == 0;
    mp.fracture = i % 4 == 1;
    mp.regions = i % 5 == 2 ? 2 : 1;
    const TetSoup soup = random_classified_mesh(mp);
    PipelineParams p;
    p.optim.method = i % 8 == 0 ? OptimParams::Method::Untangle : OptimParams::Method::None;
    p.split.max_rounds = 1;
    const ConvertResult r = convert(soup, p);
    ASSERT_EQ(r.check.invalid_cells, 0u) << "mesh " << i;
    EXPECT_TRUE(r.check.validation.ok()) << "mesh " << i;
    if (const Json* c = split_stat(r, "closure_rounds"); c && std::stoi(c->dump(0)) > 0) ++closed_by_closure;
  }
  // Not vacuous: on some meshes one round was not enough.
  if (count >= 50) EXPECT_GT(closed_by_closure, 0u);
}

// `--no-split` leaves invalid cells: the command still writes the mesh and
// exits 0, but warns on stderr naming at most 10 cells, then "and N more",
// and --require-valid refuses it (exit 1) naming cells too.
TEST(SplitClosure, InvalidCellsWarnedOrRefused) {
  const std::string ele = wedge_cone_mesh();
  if (ele.empty()) POLYDUAL_MISSING_TOOL("gmsh or tetgen is not installed (or failed)");
  const std::string out = std::filesystem::path(ele).parent_path().string() + "/nosplit.vtu";
  std::filesystem::remove(out);
  const testing::CmdResult warned =
      testing::run_polydual("convert '" + ele + "' -o '" + out + "' --no-split --optimize none --quiet");
  EXPECT_EQ(warned.code, 0) << warned.out;
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_NE(warned.out.find("warning: " + out + " written with cells that are not star-shaped"), std::string::npos)
      << warned.out;
  const std::size_t at = warned.out.find("invalid_cells: ");
  ASSERT_NE(at, std::string::npos) << warned.out;
  const std::string line = warned.out.substr(at, warned.out.find('\n', at) - at);
  std::size_t named = 0;
  for (std::size_t k = line.find("cell "); k != std::string::npos; k = line.find("cell ", k + 1)) ++named;
  EXPECT_GE(named, 1u) << line;
  EXPECT_LE(named, 10u) << line;
  if (named == 10) EXPECT_NE(line.find(" more"), std::string::npos) << line;
  std::filesystem::remove(out);
  const testing::CmdResult refused = testing::run_polydual("convert '" + ele + "' -o '" + out +
                                                           "' --no-split --optimize none --require-valid --quiet");
  EXPECT_EQ(refused.code, 1) << refused.out;
  EXPECT_NE(refused.out.find("remain invalid"), std::string::npos) << refused.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace polydual
