// The command reaches Gmsh through its module polydual-gmsh.so only
// (lib/generate/gmsh_module.h): it does not link libgmsh or OpenCASCADE, loads
// the module only for generate (and demo), finds it beside itself and in the
// install layout, names what it looked for when it is missing or broken, and
// generates the same bytes as the library that links Gmsh directly.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "generate/domains.h"
#include "run_command.h"

namespace fs = std::filesystem;
using polydual::testing::capture;

namespace {

const fs::path kBinary = POLYDUAL_BINARY;
const fs::path kModule = kBinary.parent_path() / "polydual-gmsh.so";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A fresh directory per test under the build's temporary area.
fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("polydual_gmsh_module_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string run(const std::string& cmd, int& code) { return capture(cmd + " 2>&1", code); }

}  // namespace

TEST(GmshModule, CommandDoesNotLinkGmshOrOpenCascade) {
  int code = 0;
  const std::string libs = run("ldd " + kBinary.string(), code);
  ASSERT_EQ(code, 0) << libs;
  EXPECT_EQ(libs.find("gmsh"), std::string::npos) << libs;
  EXPECT_EQ(libs.find("libTK"), std::string::npos) << libs;  // OpenCASCADE
  ASSERT_TRUE(fs::exists(kModule));
  const std::string module_libs = run("ldd " + kModule.string(), code);
  EXPECT_NE(module_libs.find("libgmsh"), std::string::npos) << module_libs;
}

TEST(GmshModule, LoadedOnlyByGenerate) {
  const fs::path d = scratch("lazy");
  int code = 0;
  // LD_DEBUG=files lists every shared object the process opens.
  const std::string help = run("LD_DEBUG=files " + kBinary.string() + " --help", code);
  EXPECT_EQ(code, 0);
  // (the scratch paths contain "gmsh_module": look for the libraries' names)
  EXPECT_EQ(help.find("libgmsh"), std::string::npos) << help.substr(0, 2000);
  EXPECT_EQ(help.find("polydual-gmsh.so"), std::string::npos);
  const std::string conv = run("LD_DEBUG=files " + kBinary.string() + " convert " + POLYDUAL_TEST_DATA +
                                   "/cube5.msh -o " + (d / "c.vtu").string() + " --optimize none --quiet",
                               code);
  EXPECT_EQ(code, 0) << conv.substr(0, 2000);
  EXPECT_EQ(conv.find("libgmsh"), std::string::npos);
  EXPECT_EQ(conv.find("polydual-gmsh.so"), std::string::npos);
  EXPECT_EQ(conv.find("libTKernel"), std::string::npos);
  const std::string gen =
      run("LD_DEBUG=files " + kBinary.string() + " generate cube --tets 200 -o " + (d / "g.msh").string(), code);
  EXPECT_EQ(code, 0);
  EXPECT_NE(gen.find("polydual-gmsh.so"), std::string::npos);
  EXPECT_NE(gen.find("libgmsh"), std::string::npos);
  fs::remove_all(d);
}

TEST(GmshModule, MissingModuleIsAClearErrorAndOtherCommandsStillWork) {
  const fs::path d = scratch("missing");
  fs::create_directories(d / "bin");
  const fs::path lone = d / "bin" / "polydual";
  fs::copy_file(kBinary, lone);
  int code = 0;
  const std::string conv = run(lone.string() + " convert " + std::string(POLYDUAL_TEST_DATA) + "/cube5.msh -o " +
                                   (d / "c.vtu").string() + " --optimize none --quiet",
                               code);
  EXPECT_EQ(code, 0) << conv;
  EXPECT_TRUE(fs::exists(d / "c.vtu"));
  const std::string gen = run(lone.string() + " generate cube --tets 200 -o " + (d / "g.msh").string(), code);
  EXPECT_EQ(code, 1) << gen;
  EXPECT_NE(gen.find("polydual-gmsh.so"), std::string::npos) << gen;
  EXPECT_NE(gen.find("was not found"), std::string::npos) << gen;
  EXPECT_NE(gen.find((d / "bin" / "polydual-gmsh.so").string()), std::string::npos) << gen;
  EXPECT_NE(gen.find((d / "lib" / "polydual" / "polydual-gmsh.so").string()), std::string::npos) << gen;
  EXPECT_FALSE(fs::exists(d / "g.msh"));
  const std::string demo = run(lone.string() + " demo --tets 200 --domains cube --out " + (d / "demo").string(), code);
  EXPECT_EQ(code, 1) << demo;
  EXPECT_NE(demo.find("was not found"), std::string::npos) << demo;
  fs::remove_all(d);
}

TEST(GmshModule, FoundInTheInstallLayout) {
  const fs::path d = scratch("installed");
  fs::create_directories(d / "bin");
  fs::create_directories(d / "lib" / "polydual");
  fs::copy_file(kBinary, d / "bin" / "polydual");
  fs::copy_file(kModule, d / "lib" / "polydual" / "polydual-gmsh.so");
  int code = 0;
  const std::string gen =
      run((d / "bin" / "polydual").string() + " generate cube --tets 200 -o " + (d / "g.msh").string(), code);
  EXPECT_EQ(code, 0) << gen;
  EXPECT_TRUE(fs::exists(d / "g.msh"));
  fs::remove_all(d);
}

TEST(GmshModule, BrokenModuleNamedInTheError) {
  const fs::path d = scratch("broken");
  {
    std::ofstream(d / "bad.so") << "not an ELF file\n";
  }
  int code = 0;
  const std::string gen = run("POLYDUAL_GMSH_MODULE=" + (d / "bad.so").string() + " " + kBinary.string() +
                                  " generate cube --tets 200 -o " + (d / "g.msh").string(),
                              code);
  EXPECT_EQ(code, 1) << gen;
  EXPECT_NE(gen.find("cannot load the Gmsh module " + (d / "bad.so").string()), std::string::npos) << gen;
  // An explicit path is the only place looked in.
  const std::string missing = run("POLYDUAL_GMSH_MODULE=" + (d / "none.so").string() + " " + kBinary.string() +
                                      " generate cube --tets 200 -o " + (d / "g.msh").string(),
                                  code);
  EXPECT_EQ(code, 1) << missing;
  EXPECT_NE(missing.find("looked for " + (d / "none.so").string() + " ("), std::string::npos) << missing;
  EXPECT_FALSE(fs::exists(d / "g.msh"));
  fs::remove_all(d);
}

// The command (through the module) and the linked library give the same file
// and the same mesh.
TEST(GmshModule, SameMeshAsTheLinkedLibrary) {
  const fs::path d = scratch("same");
  int code = 0;
  for (const char* domain : {"twomat", "fracture"}) {
    const fs::path by_cmd = d / (std::string(domain) + "_cmd.msh"), by_lib = d / (std::string(domain) + "_lib.msh");
    const std::string out =
        run(kBinary.string() + " generate " + domain + " --tets 800 -o " + by_cmd.string(), code);
    ASSERT_EQ(code, 0) << out;
    polydual::write_domain_msh(polydual::parse_domain(domain), 800, by_lib.string());
    EXPECT_EQ(slurp(by_cmd), slurp(by_lib)) << domain;
    EXPECT_GT(slurp(by_cmd).size(), 1000u);
  }
  fs::remove_all(d);
}
