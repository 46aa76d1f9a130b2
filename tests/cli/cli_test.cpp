// The polydual command end to end: exit codes, no half-written outputs,
// byte-identical outputs on repeated runs, JSON keys.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "run_command.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {
using polydual::testing::CmdResult;
CmdResult run(const std::string& args) { return polydual::testing::run_polydual(args); }
std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}
fs::path scratch() {
  fs::path d = fs::temp_directory_path() / ("polydual_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST(Cli, HelpAndUsageErrors) {
  for (const char* c : {"demo", "generate", "info", "convert", "check", "optimize"}) {
    CmdResult r = run(std::string(c) + " --help");
    EXPECT_EQ(r.code, 0) << c;
    EXPECT_THAT(r.out, HasSubstr("usage: polydual")) << c;
  }
  EXPECT_EQ(run("").code, 2);
  EXPECT_EQ(run("frobnicate").code, 2);
  CmdResult r = run("convert x.msh -o y.vtu --no-such-option");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("unknown option '--no-such-option'"));
  r = run("generate klein_bottle --tets 1000 -o k.msh");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, HasSubstr("klein_bottle"));
}

TEST(Cli, BadInputNamesTheFileAndWritesNothing) {
  const fs::path d = scratch();
  {
    std::ofstream f(d / "bad.mesh");
    f << "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\nnan 1 0 1\n0 0 1 1\nEnd\n";
  }
  CmdResult r = run("convert " + (d / "bad.mesh").string() + " -o " + (d / "out.vtu").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.out, HasSubstr("bad.mesh"));
  EXPECT_THAT(r.out, HasSubstr("line 7"));
  EXPECT_FALSE(fs::exists(d / "out.vtu"));
  for (auto& e : fs::directory_iterator(d)) EXPECT_THAT(e.path().filename().string(), ::testing::Not(HasSubstr(".tmp.")));
  fs::remove_all(d);
}

TEST(Cli, GenerateInfoConvertCheckAreDeterministic) {
  const fs::path d = scratch();
  ASSERT_EQ(run("generate fracture --tets 2000 -o " + (d / "f.msh").string()).code, 0);
  CmdResult info = run("info " + (d / "f.msh").string() + " --json");
  ASSERT_EQ(info.code, 0) << info.out;
  for (const char* k : {"\"tets\"", "\"vertices\"", "\"model\"", "\"regions\"", "\"faces\"", "\"edges\""})
    EXPECT_THAT(info.out, HasSubstr(k));
  for (int i = 0; i < 2; ++i) {
    const std::string tag = std::to_string(i);
    CmdResult c = run("convert " + (d / "f.msh").string() + " -o " + (d / ("f" + tag + ".vtu")).string() +
                " --optimize none --json");
    ASSERT_EQ(c.code, 0) << c.out;
    for (const char* k : {"\"cells\"", "\"faces\"", "\"points\"", "\"invalid_cells\"", "\"closed_cells\"",
                          "\"materials\"", "\"primal_volume\"", "\"seconds\""})
      EXPECT_THAT(c.out, HasSubstr(k));
    ASSERT_EQ(run("convert " + (d / "f.msh").string() + " -o " + (d / ("case" + tag)).string() +
                  " --format foam --optimize none").code, 0);
  }
  EXPECT_EQ(slurp(d / "f0.vtu"), slurp(d / "f1.vtu"));
  // With the default optimisation (parallel coloured sweeps) too.
  for (const char* name : {"o0.vtu", "o1.vtu"})
    ASSERT_EQ(run("convert " + (d / "f.msh").string() + " -o " + (d / name).string()).code, 0);
  EXPECT_EQ(slurp(d / "o0.vtu"), slurp(d / "o1.vtu"));
  EXPECT_NE(slurp(d / "o0.vtu"), slurp(d / "f0.vtu"));  // the optimiser did move points
  for (const char* f : {"points", "faces", "owner", "neighbour", "boundary", "cellZones", "faceZones"})
    EXPECT_EQ(slurp(d / "case0/constant/polyMesh" / f), slurp(d / "case1/constant/polyMesh" / f)) << f;
  CmdResult chk = run("check " + (d / "f0.vtu").string() + " --json");
  EXPECT_EQ(chk.code, 0) << chk.out;
  EXPECT_THAT(chk.out, HasSubstr("\"invalid_cells\""));
  fs::remove_all(d);
}
