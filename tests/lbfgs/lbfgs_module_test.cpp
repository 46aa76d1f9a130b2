// The command reaches Ceres' solver through its module polydual-lbfgs.so only
// (lib/lbfgs/lbfgs_module.h): it does not link Ceres' libraries (BLAS,
// LAPACK, SuiteSparse, glog, gflags), loads the module only for
// `--optimize global`, names what it looked for when the module is missing,
// and optimises to the same points as the library that links Ceres directly.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/vtu_poly_reader.h"
#include "pipeline/convert.h"
#include "run_command.h"

namespace fs = std::filesystem;
using polydual::testing::capture;

namespace {

const fs::path kBinary = POLYDUAL_BINARY;
const fs::path kModule = kBinary.parent_path() / "polydual-lbfgs.so";
const std::string kCube = std::string(POLYDUAL_TEST_DATA) + "/cube5.msh";

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("polydual_lbfgs_module_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string run(const std::string& cmd, int& code) { return capture(cmd + " 2>&1", code); }

}  // namespace

TEST(LbfgsModule, CommandDoesNotLinkCeresLibraries) {
  int code = 0;
  const std::string libs = run("ldd " + kBinary.string(), code);
  ASSERT_EQ(code, 0) << libs;
  for (const char* lib : {"libglog", "libgflags", "libcholmod", "liblapack", "libblas", "libgfortran"})
    EXPECT_EQ(libs.find(lib), std::string::npos) << lib << "\n" << libs;
  ASSERT_TRUE(fs::exists(kModule));
  const std::string module_libs = run("ldd " + kModule.string(), code);
  EXPECT_NE(module_libs.find("libglog"), std::string::npos) << module_libs;
}

TEST(LbfgsModule, LoadedOnlyByTheGlobalScheme) {
  const fs::path d = scratch("lazy");
  int code = 0;
  for (const char* method : {"none", "local"}) {
    const std::string out = run("LD_DEBUG=files " + kBinary.string() + " convert " + kCube + " -o " +
                                    (d / "c.vtu").string() + " --optimize " + method + " --quiet",
                                code);
    EXPECT_EQ(code, 0) << out.substr(0, 2000);
    EXPECT_EQ(out.find("polydual-lbfgs.so"), std::string::npos) << method;
    EXPECT_EQ(out.find("libcholmod"), std::string::npos) << method;
  }
  const std::string global = run("LD_DEBUG=files " + kBinary.string() + " convert " + kCube + " -o " +
                                     (d / "g.vtu").string() + " --optimize global --quiet",
                                 code);
  EXPECT_EQ(code, 0) << global.substr(0, 2000);
  EXPECT_NE(global.find("polydual-lbfgs.so"), std::string::npos);
  EXPECT_NE(global.find("libcholmod"), std::string::npos);
  fs::remove_all(d);
}

TEST(LbfgsModule, MissingModuleIsAClearErrorAndOtherSchemesStillWork) {
  const fs::path d = scratch("missing");
  fs::create_directories(d / "bin");
  const fs::path lone = d / "bin" / "polydual";
  fs::copy_file(kBinary, lone);
  int code = 0;
  const std::string local =
      run(lone.string() + " convert " + kCube + " -o " + (d / "c.vtu").string() + " --optimize local --quiet", code);
  EXPECT_EQ(code, 0) << local;
  EXPECT_TRUE(fs::exists(d / "c.vtu"));
  const std::string global =
      run(lone.string() + " convert " + kCube + " -o " + (d / "g.vtu").string() + " --optimize global", code);
  EXPECT_EQ(code, 1) << global;
  EXPECT_NE(global.find("polydual-lbfgs.so"), std::string::npos) << global;
  EXPECT_NE(global.find("was not found"), std::string::npos) << global;
  EXPECT_NE(global.find((d / "bin" / "polydual-lbfgs.so").string()), std::string::npos) << global;
  EXPECT_NE(global.find((d / "lib" / "polydual" / "polydual-lbfgs.so").string()), std::string::npos) << global;
  EXPECT_FALSE(fs::exists(d / "g.vtu"));
  // Found through POLYDUAL_LBFGS_MODULE.
  const std::string named = run("POLYDUAL_LBFGS_MODULE=" + kModule.string() + " " + lone.string() + " convert " +
                                    kCube + " -o " + (d / "g.vtu").string() + " --optimize global --quiet",
                                code);
  EXPECT_EQ(code, 0) << named;
  EXPECT_TRUE(fs::exists(d / "g.vtu"));
  fs::remove_all(d);
}

// The command (through the module) and the library (linked with Ceres) move
// the points to the same coordinates, bit for bit.
TEST(LbfgsModule, SamePointsAsTheLinkedLibrary) {
  using namespace polydual;
  const fs::path d = scratch("same");
  int code = 0;
  const std::string out = run(kBinary.string() + " convert " + kCube + " -o " + (d / "cmd.vtu").string() +
                                  " --optimize global --quiet",
                              code);
  ASSERT_EQ(code, 0) << out;
  PipelineParams params;
  params.optim.method = OptimParams::Method::Global;
  const ConvertResult r = convert_file(kCube, (d / "lib.vtu").string(), PolyFormat::Vtu, params);
  ASSERT_GT(r.report.stage("optimize") ? 1 : 0, 0);
  const PolyMesh a = read_vtu_poly((d / "cmd.vtu").string()), b = read_vtu_poly((d / "lib.vtu").string());
  ASSERT_EQ(a.num_points(), b.num_points());
  std::size_t differ = 0;
  for (std::size_t p = 0; p < a.num_points(); ++p) differ += !(a.points[p] == b.points[p]);
  EXPECT_EQ(differ, 0u);
  // and the optimiser did move them: the raw dual differs.
  params.optim.method = OptimParams::Method::None;
  const ConvertResult raw = convert_file(kCube, (d / "raw.vtu").string(), PolyFormat::Vtu, params);
  ASSERT_EQ(raw.mesh.num_points(), a.num_points());
  std::size_t moved = 0;
  for (std::size_t p = 0; p < a.num_points(); ++p) moved += !(raw.mesh.points[p] == a.points[p]);
  EXPECT_GT(moved, 0u);
  fs::remove_all(d);
}
