// Every option of every subcommand, checked by its effect on the outputs (not
// only by being accepted): the option table (lib/cli/options.cpp) is shared,
// so each test here pins what one option does where it is used.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "run_command.h"
#include "split/split.h"
#include "scratch_dir.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <vector>

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

struct CmdResult {
  int code;
  std::string out;  // stdout only
  std::string err;  // stderr
};

fs::path scratch_root() { return polydual::test::scratch_dir(); }

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

using polydual::testing::capture;

CmdResult run(const std::string& args) {
  static int counter = 0;
  const fs::path err = scratch_root() / ("stderr_" + std::to_string(counter++));
  CmdResult r{0, {}, {}};
  r.out = capture(std::string(POLYDUAL_BINARY) + " " + args + " 2>" + err.string(), r.code);
  r.err = slurp(err);
  return r;
}

// Evaluates a Python expression over the JSON document `json` (bound to d).
std::string jq(const std::string& json, const std::string& expr) {
  static int counter = 0;
  const fs::path f = scratch_root() / ("doc_" + std::to_string(counter++) + ".json");
  std::ofstream(f) << json;
  const fs::path py = f.string() + ".py";
  std::ofstream(py) << "import json\nd = json.load(open('" << f.string() << "'))\nprint(" << expr << ")\n";
  int code = 0;
  std::string out = capture("/usr/bin/python3 " + py.string() + " 2>&1", code);
  EXPECT_EQ(code, 0) << expr << ": " << out;
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}
double jnum(const std::string& json, const std::string& expr) { return std::stod(jq(json, expr)); }

// Test meshes made once by the command itself: a fully classified msh 4.1
// file, and a TetGen .node/.ele pair without .face (region tags only, so the
// classification is inferred and the feature angle applies).
struct Meshes {
  fs::path msh, node;
};
const Meshes& meshes() {
  static const Meshes m = [] {
    Meshes r{scratch_root() / "twomat.msh", scratch_root() / "fichera.node"};
    EXPECT_EQ(run("generate twomat --tets 3000 -o " + r.msh.string()).code, 0);
    EXPECT_EQ(run("generate fichera --tets 2000 -o " + r.node.string()).code, 0);
    fs::remove(scratch_root() / "fichera.face");
    return r;
  }();
  return m;
}

std::string convert_json(const std::string& opts, const std::string& out_name = "c.vtu") {
  CmdResult r = run("convert " + meshes().msh.string() + " -o " + (scratch_root() / out_name).string() +
                    " --json " + opts);
  EXPECT_EQ(r.code, 0) << opts << ": " << r.err;
  return r.out;
}

}  // namespace

TEST(CliOptions, HelpListsEveryOptionWithItsDefault) {
  struct Expect {
    const char* command;
    std::vector<std::string> lines;
  };
  const Expect cases[] = {
      {"convert", {"-o OUT", "--format vtu|foam", "--feature-angle DEG", "(default 30)", "--boundary keep|caps", "--no-cleanup",
                   "--collapse-tol X", "(default 0.001)", "--optimize auto|none|untangle|local|global", "(default auto)",
                   "--metric q1|q2", "(default q1)", "--derivatives corrected|analytic|lagged|fd|exact", "(default corrected)",
                   "--max-iter N", "(default 20)", "--threads N", "--json"}},
      {"generate", {"--tets N", "(default 10000)", "-o OUT", "--threads N", "--quiet"}},
      {"demo", {"--tets N", "(default 20000)", "--out DIR", "(default polydual-demo)", "--domains LIST"}},
      {"info", {"--feature-angle DEG", "--json", "--threads N", "--quiet"}},
      {"check", {"--json", "--threads N", "--quiet"}},
      {"optimize", {"--primal MESH", "--optimize", "--max-iter N"}},
  };
  for (const Expect& e : cases) {
    CmdResult r = run(std::string(e.command) + " --help");
    ASSERT_EQ(r.code, 0) << e.command;
    for (const std::string& l : e.lines) EXPECT_THAT(r.out, HasSubstr(l)) << e.command;
  }
}

TEST(CliOptions, ValuesAreCheckedForTypeAndRange) {
  const std::string in = meshes().msh.string(), out = (scratch_root() / "bad.vtu").string();
  for (const char* bad : {"--feature-angle abc", "--feature-angle 200", "--feature-angle 0", "--collapse-tol 0.9",
                          "--max-iter -1", "--max-iter 1.5", "--optimize fast", "--metric q3",
                          "--derivatives magic", "--threads -2", "--format stl", "--json=1"}) {
    CmdResult r = run("convert " + in + " -o " + out + " " + bad);
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_THAT(r.err, HasSubstr("usage error")) << bad;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
  // A value may also be given as --name=value.
  EXPECT_EQ(run("convert " + in + " -o " + out + " --optimize=none").code, 0);
  EXPECT_TRUE(fs::exists(out));
}

TEST(CliOptions, ConvertOutputAndFormat) {
  const std::string in = meshes().msh.string();
  const fs::path d = scratch_root();
  ASSERT_EQ(run("convert " + in + " -o " + (d / "f.vtu").string() + " --optimize none").code, 0);
  EXPECT_THAT(slurp(d / "f.vtu"), HasSubstr("<VTKFile type=\"UnstructuredGrid\""));
  // No extension: an OpenFOAM case; --format overrides the name.
  ASSERT_EQ(run("convert " + in + " -o " + (d / "case_a").string() + " --optimize none").code, 0);
  EXPECT_TRUE(fs::exists(d / "case_a/constant/polyMesh/owner"));
  ASSERT_EQ(run("convert " + in + " -o " + (d / "plain_vtu").string() + " --format vtu --optimize none").code, 0);
  EXPECT_THAT(slurp(d / "plain_vtu"), HasSubstr("<VTKFile"));
  // An extension that is no polyhedral format is refused, nothing written.
  CmdResult r = run("convert " + in + " -o " + (d / "out.msh").string() + " --optimize none");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("unsupported extension"));
  EXPECT_FALSE(fs::exists(d / "out.msh"));
  EXPECT_EQ(run("convert " + in + " --optimize none").code, 2);  // -o is required
}

TEST(CliOptions, FeatureAngleSplitsInferredModelFaces) {
  const std::string node = meshes().node.string();
  CmdResult sharp = run("info " + node + " --json");
  CmdResult flat = run("info " + node + " --json --feature-angle 180");
  ASSERT_EQ(sharp.code, 0) << sharp.err;
  ASSERT_EQ(flat.code, 0) << flat.err;
  // Fichera's boundary has 9 planar faces; at 180 degrees nothing splits.
  EXPECT_EQ(jnum(sharp.out, "d['model']['faces']"), 9);
  EXPECT_EQ(jnum(flat.out, "d['model']['faces']"), 1);
  EXPECT_EQ(jnum(flat.out, "d['params']['feature_angle_deg']"), 180);
  // The same through convert (model summary and params).
  CmdResult c = run("convert " + node + " -o " + (scratch_root() / "fa.vtu").string() +
                    " --optimize none --json --feature-angle 180");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(jnum(c.out, "d['model']['faces']"), 1);
  EXPECT_EQ(jnum(c.out, "d['params']['feature_angle_deg']"), 180);
}

TEST(CliOptions, CleanupOptions) {
  const std::string base = convert_json("--optimize none");
  const std::string none = convert_json("--optimize none --no-cleanup");
  const std::string zero = convert_json("--optimize none --collapse-tol 0");
  const std::string big = convert_json("--optimize none --collapse-tol 0.3");
  EXPECT_EQ(jq(none, "d['params']['cleanup']"), "False");
  EXPECT_EQ(jnum(none, "d['dual']['collapsed_points'] + d['dual']['merged_points']"), 0);
  EXPECT_EQ(jnum(zero, "d['dual']['collapsed_points']"), 0);
  EXPECT_GT(jnum(big, "d['dual']['collapsed_points']"), jnum(base, "d['dual']['collapsed_points']"));
  EXPECT_LT(jnum(big, "d['points']"), jnum(base, "d['points']"));
  EXPECT_EQ(jnum(big, "d['params']['collapse_tolerance']"), 0.3);
  EXPECT_EQ(jnum(none, "d['points']"), jnum(base, "d['points']") + jnum(base, "d['dual']['collapsed_points']") +
                                           jnum(base, "d['dual']['merged_points']"));
}

TEST(CliOptions, OptimizerOptions) {
  const std::string none = convert_json("--optimize none --no-split", "o_none.vtu");
  EXPECT_EQ(jq(none, "d['optimize']"), "None");
  EXPECT_EQ(jnum(none, "d['invalid_before']"), jnum(none, "d['invalid_after']"));
  ASSERT_GT(jnum(none, "d['invalid_before']"), 0);  // so untangling has something to do

  const std::string local = convert_json("--optimize local", "o_local.vtu");
  EXPECT_EQ(jq(local, "d['params']['optimize']"), "local");
  EXPECT_LT(jnum(local, "d['invalid_after']"), jnum(local, "d['invalid_before']"));
  EXPECT_GT(jnum(local, "d['optimize']['colours']"), 0);  // the local scheme's independent sets

  const std::string global = convert_json("--optimize global --max-iter 3", "o_global.vtu");
  EXPECT_EQ(jq(global, "d['params']['optimizer']['method']"), "global");
  EXPECT_LT(jnum(global, "d['invalid_after']"), jnum(global, "d['invalid_before']"));
  EXPECT_NE(slurp(scratch_root() / "o_local.vtu"), slurp(scratch_root() / "o_global.vtu"));

  const std::string q2 = convert_json("--metric q2 --max-iter 2");
  EXPECT_EQ(jq(q2, "d['optimize']['quality_before']['metric']"), "q2");
  EXPECT_EQ(jq(local, "d['optimize']['quality_before']['metric']"), "q1");

  const std::string one = convert_json("--max-iter 1");
  EXPECT_EQ(jnum(one, "d['params']['max_iter']"), 1);
  // The initial state, one sweep and at most the OpenFOAM-gate repair's record.
  EXPECT_LE(jnum(one, "len(d['optimize']['iterations'])"), 3);
  EXPECT_GT(jnum(local, "len(d['optimize']['iterations'])"), 2);

  convert_json("--max-iter 3 --derivatives fd", "o_fd.vtu");
  convert_json("--max-iter 3 --derivatives analytic", "o_an.vtu");
  const std::string fd = convert_json("--max-iter 3 --derivatives fd");
  EXPECT_EQ(jq(fd, "d['params']['derivatives']"), "fd");
  // Same objective, other derivative approximations: other point positions.
  EXPECT_NE(slurp(scratch_root() / "o_fd.vtu"), slurp(scratch_root() / "o_an.vtu"));
}

TEST(CliOptions, ThreadsDoNotChangeOutputs) {
  const std::string in = meshes().msh.string();
  const fs::path d = scratch_root();
  for (const char* t : {"1", "2", "3"})
    ASSERT_EQ(run("convert " + in + " -o " + (d / (std::string("t") + t + ".vtu")).string() +
                  " --max-iter 3 --threads " + t).code, 0);
  EXPECT_EQ(slurp(d / "t1.vtu"), slurp(d / "t2.vtu"));
  EXPECT_EQ(slurp(d / "t1.vtu"), slurp(d / "t3.vtu"));
}

// `--threads N` and `--quiet` on every command; the outputs do not
// depend on the thread count, and --quiet leaves stderr empty.
TEST(CliOptions, EveryCommandTakesThreadsAndQuiet) {
  const fs::path d = scratch_root();
  const std::string vtu1 = (d / "g1.vtu").string(), vtu2 = (d / "g2.vtu").string();
  CmdResult g1 = run("generate fichera --tets 1500 -o " + vtu1 + " --threads 1 --quiet");
  CmdResult g2 = run("generate fichera --tets 1500 -o " + vtu2 + " --threads 2");
  ASSERT_EQ(g1.code, 0) << g1.err;
  ASSERT_EQ(g2.code, 0) << g2.err;
  EXPECT_EQ(g1.err, "");
  EXPECT_THAT(g2.err, HasSubstr("polydual: wrote"));  // the line --quiet removes
  EXPECT_EQ(slurp(vtu1), slurp(vtu2));
  const std::string in = meshes().msh.string(), out = (d / "q.vtu").string();
  ASSERT_EQ(run("convert " + in + " -o " + out + " --optimize none --quiet").code, 0);
  const std::vector<std::string> commands = {"info " + in, "check " + out, "convert " + in + " -o " + out +
                                             " --optimize none --force", "optimize " + out + " --primal " + in +
                                             " -o " + (d / "q2.vtu").string() + " --max-iter 1"};
  for (const std::string& c : commands) {
    CmdResult one = run(c + " --json --quiet --threads 1"), two = run(c + " --json --quiet --threads 2");
    ASSERT_EQ(one.code, 0) << c << ": " << one.err;
    ASSERT_EQ(two.code, 0) << c << ": " << two.err;
    EXPECT_EQ(one.err, "") << c;
    EXPECT_EQ(jq(one.out, "d.get('cells', d.get('tets'))"), jq(two.out, "d.get('cells', d.get('tets'))")) << c;
  }
}

TEST(CliOptions, JsonOrText) {
  const std::string in = meshes().msh.string(), out = (scratch_root() / "j.vtu").string();
  CmdResult text = run("convert " + in + " -o " + out + " --optimize none");
  ASSERT_EQ(text.code, 0);
  EXPECT_THAT(text.out, HasSubstr("invalid cells (exact star test)"));
  EXPECT_THAT(text.out, Not(HasSubstr("\"invalid_before\"")));
  const std::string json = convert_json("--optimize none", "j.vtu");
  EXPECT_EQ(jq(json, "d['output']['format']"), "vtu");
  EXPECT_EQ(jq(json, "sorted(d['seconds'].keys()) == sorted(['read', 'classify', 'optimize_tets', 'cuts', 'dual', 'star_test', 'split', 'check_split', "
                     "'openfoam_check', 'write', 'total', 'stages'])"),
            "True");
  EXPECT_EQ(jq(json, "list(d['seconds']['stages'].keys())"),
            "['read', 'classify', 'optimize_tets', 'cuts', 'dual', 'cleanup', 'cells', 'check', 'split', 'check_split', 'openfoam_check', 'write']");
  CmdResult chk = run("check " + out + " --json");
  ASSERT_EQ(chk.code, 0) << chk.err;
  EXPECT_EQ(jnum(chk.out, "d['cells']"), jnum(json, "d['cells']"));
  EXPECT_EQ(jnum(chk.out, "d['invalid_cells']"), jnum(json, "d['invalid_after']"));
  CmdResult chk_text = run("check " + out);
  EXPECT_THAT(chk_text.out, HasSubstr("cells,"));
}

TEST(CliOptions, GenerateTetsAndOutput) {
  const fs::path d = scratch_root();
  ASSERT_EQ(run("generate cube --tets 500 -o " + (d / "s.msh").string()).code, 0);
  ASSERT_EQ(run("generate cube --tets 4000 -o " + (d / "l.msh").string()).code, 0);
  const double small = jnum(run("info " + (d / "s.msh").string() + " --json").out, "d['tets']");
  const double large = jnum(run("info " + (d / "l.msh").string() + " --json").out, "d['tets']");
  EXPECT_GT(small, 500 * 0.6);
  EXPECT_LT(small, 500 * 1.4);
  EXPECT_GT(large, 4000 * 0.6);
  EXPECT_LT(large, 4000 * 1.4);
  EXPECT_EQ(run("generate cube --tets 50 -o " + (d / "x.msh").string()).code, 2);  // below the range
  EXPECT_EQ(run("generate cube --tets 500").code, 2);                               // -o required
}

TEST(CliOptions, OptimizeCommand) {
  const fs::path d = scratch_root();
  const std::string msh = meshes().msh.string();
  ASSERT_EQ(run("convert " + msh + " -o " + (d / "raw.vtu").string() + " --optimize none --no-split").code, 0);
  const std::string raw = (d / "raw.vtu").string();
  CmdResult fixed = run("optimize " + raw + " -o " + (d / "fixed.vtu").string() + " --max-iter 3 --json");
  ASSERT_EQ(fixed.code, 0) << fixed.err;
  CmdResult slide = run("optimize " + raw + " -o " + (d / "slide.vtu").string() + " --max-iter 3 --json --primal " + msh);
  ASSERT_EQ(slide.code, 0) << slide.err;
  // With the primal, boundary points may slide: the outputs differ.
  EXPECT_NE(slurp(d / "fixed.vtu"), slurp(d / "slide.vtu"));
  EXPECT_LT(jnum(fixed.out, "d['invalid_after']"), jnum(fixed.out, "d['invalid_before']"));
  // Zero iterations leave the points where they were (same cells and verdicts).
  CmdResult zero = run("optimize " + raw + " -o " + (d / "zero.vtu").string() + " --max-iter 0 --json");
  ASSERT_EQ(zero.code, 0) << zero.err;
  EXPECT_EQ(jnum(zero.out, "d['invalid_after']"), jnum(zero.out, "d['invalid_before']"));
  CmdResult global = run("optimize " + raw + " -o " + (d / "glob.vtu").string() +
                         " --optimize global --max-iter 2 --metric q2 --json");
  ASSERT_EQ(global.code, 0) << global.err;
  EXPECT_EQ(jq(global.out, "d['optimize']['quality_before']['metric']"), "q2");
  EXPECT_NE(slurp(d / "glob.vtu"), slurp(d / "fixed.vtu"));
  CmdResult fd = run("optimize " + raw + " -o " + (d / "fd.vtu").string() + " --max-iter 3 --derivatives fd");
  ASSERT_EQ(fd.code, 0) << fd.err;
  EXPECT_NE(slurp(d / "fd.vtu"), slurp(d / "fixed.vtu"));
  // --feature-angle applies to the primal's inferred classification.
  const std::string node = meshes().node.string();
  ASSERT_EQ(run("convert " + node + " -o " + (d / "fraw.vtu").string() + " --optimize none").code, 0);
  ASSERT_EQ(run("optimize " + (d / "fraw.vtu").string() + " -o " + (d / "f30.vtu").string() +
                " --max-iter 3 --primal " + node).code, 0);
  ASSERT_EQ(run("optimize " + (d / "fraw.vtu").string() + " -o " + (d / "f180.vtu").string() +
                " --max-iter 3 --feature-angle 180 --primal " + node).code, 0);
  EXPECT_NE(slurp(d / "f30.vtu"), slurp(d / "f180.vtu"));
  EXPECT_EQ(run("optimize " + raw + " -o " + (d / "x.msh").string()).code, 2);  // VTU only
}

TEST(CliOptions, DemoOptions) {
  const fs::path d = scratch_root() / "demo";
  CmdResult r = run("demo --out " + d.string() + " --tets 400 --domains cube,fracture --optimize none --threads 2");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"cube.msh", "cube.vtu", "cube_case/constant/polyMesh/owner", "fracture.vtu", "summary.json"})
    EXPECT_TRUE(fs::exists(d / f)) << f;
  EXPECT_FALSE(fs::exists(d / "twomat.vtu"));
  const std::string summary = slurp(d / "summary.json");
  EXPECT_EQ(jnum(summary, "len(d)"), 2);
  EXPECT_EQ(jq(summary, "[x['params']['optimize'] for x in d]"), "['none', 'none']");
  // Without the optimiser the split alone leaves every cell valid.
  EXPECT_EQ(jq(summary, "all(x['invalid_after'] == 0 for x in d)"), "True");
  EXPECT_EQ(jq(summary, "any(x['invalid_before'] > 0 for x in d)"), "True");
  EXPECT_EQ(jq(summary, "all(x['recheck']['cells'] == x['cells'] for x in d)"), "True");
  EXPECT_EQ(jq(summary, "all(200 < x['tets'] < 800 for x in d)"), "True");
  EXPECT_THAT(r.out, HasSubstr("fracture"));
  EXPECT_EQ(run("demo --out " + d.string() + " --domains klein").code, 2);
}

TEST(CliOptions, DemoWritesOnlyIntoItsOwnOrAnEmptyDirectory) {
  const fs::path d = scratch_root() / "demo_user";
  fs::create_directories(d);
  std::ofstream(d / "summary.json") << "the user's own";
  std::ofstream(d / "notes.txt") << "keep me";
  const std::string args = " --tets 300 --domains cube --optimize none";
  CmdResult r = run("demo --out " + d.string() + args);
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("is not from an earlier demo"));
  EXPECT_EQ(slurp(d / "summary.json"), "the user's own");
  EXPECT_FALSE(fs::exists(d / "cube.vtu"));
  // A demo's own directory is rerun without a word; a stranger in it is refused.
  const fs::path own = scratch_root() / "demo_own";
  ASSERT_EQ(run("demo --out " + own.string() + args).code, 0);
  EXPECT_TRUE(fs::exists(own / ".polydual-demo"));
  EXPECT_EQ(run("demo --out " + own.string() + args).code, 0);
  std::ofstream(own / "notes.txt") << "keep me";
  r = run("demo --out " + own.string() + args);
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("'notes.txt', which a demo does not write"));
  // --force writes the demo's names beside the user's files.
  r = run("demo --out " + d.string() + args + " --force");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(d / "notes.txt"), "keep me");
  EXPECT_TRUE(fs::exists(d / "cube.vtu"));
  // A missing parent is refused, not created.
  r = run("demo --out " + (scratch_root() / "nope" / "deeper").string() + args);
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("does not exist"));
  EXPECT_FALSE(fs::exists(scratch_root() / "nope"));
}

TEST(CliOptions, AnOptionGivenTwiceIsAUsageError) {
  const std::string in = meshes().msh.string();
  const fs::path a = scratch_root() / "twice_a.vtu", b = scratch_root() / "twice_b.vtu";
  for (const std::string& extra : std::vector<std::string>{"-o " + b.string(), "--optimize local", "--threads 2"}) {
    CmdResult r = run("convert " + in + " -o " + a.string() + " --optimize none --threads 1 " + extra);
    EXPECT_EQ(r.code, 2) << extra;
    EXPECT_THAT(r.err, HasSubstr("is given twice; give it once")) << extra << r.err;
  }
  EXPECT_FALSE(fs::exists(a));
  EXPECT_FALSE(fs::exists(b));
}

TEST(CliOptions, ProgressOnStderrUnlessQuiet) {
  const std::string in = meshes().msh.string(), out = (scratch_root() / "p.vtu").string();
  // POLYDUAL_PROGRESS_DELAY=0 shows every step (the default shows stages
  // that have run for 2 s); stderr is not a terminal here: plain lines.
  CmdResult shown = run("convert " + in + " -o " + out + " --max-iter 3 --json 2>&1 >/dev/null | cat >&2; "
                        "POLYDUAL_PROGRESS_DELAY=0 " POLYDUAL_BINARY " convert " + in + " -o " + out + " --max-iter 3");
  ASSERT_EQ(shown.code, 0) << shown.err;
  EXPECT_THAT(shown.err, HasSubstr("polydual: optimize 1/3: invalid cells"));
  EXPECT_THAT(shown.err, HasSubstr("mean quality"));
  CmdResult quiet = run("convert " + in + " -o " + out + " --max-iter 3 --quiet; POLYDUAL_PROGRESS_DELAY=0 " POLYDUAL_BINARY
                        " convert " + in + " -o " + out + " --max-iter 3 --quiet");
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  // The split's rounds report too (here without the optimiser, which leaves
  // cells for the split): round, invalid cells, vertices cut whole.
  CmdResult split = run("convert " + in + " -o " + out + " --optimize none --json 2>&1 >/dev/null | cat >&2; "
                        "POLYDUAL_PROGRESS_DELAY=0 " POLYDUAL_BINARY " convert " + in + " -o " + out + " --optimize none");
  ASSERT_EQ(split.code, 0) << split.err;
  EXPECT_THAT(split.err, HasSubstr("polydual: split 1/64: invalid cells"));
  EXPECT_THAT(split.err, HasSubstr("vertices cut whole"));
  // A short run with the default delay prints no progress at all.
  CmdResult fast = run("convert " + in + " -o " + out + " --optimize none");
  EXPECT_THAT(fast.err, Not(HasSubstr("polydual: optimize")));
  EXPECT_THAT(fast.err, Not(HasSubstr("polydual: split")));
}

TEST(CliOptions, IgnoredEntitiesAreCountedAndWarned) {
  // Gmsh writes the part of a fragmented sheet that lies outside the volume,
  // and construction points: dropped, counted, one warning line each.
  const std::string sheet = std::string(POLYDUAL_TEST_DATA) + "/gmsh/sheet_save_all.msh";
  CmdResult info = run("info " + sheet + " --json");
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_GT(jnum(info.out, "sum(d['ignored'].values())"), 0);
  EXPECT_THAT(info.err, HasSubstr("polydual: warning: "));
  EXPECT_THAT(info.err, HasSubstr("sheet_save_all.msh"));
  CmdResult c = run("convert " + sheet + " -o " + (scratch_root() / "sheet.vtu").string() + " --optimize none --json");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(jq(c.out, "d['ignored']"), jq(info.out, "d['ignored']"));
  EXPECT_GT(jnum(c.out, "len(d['warnings'])"), 0);
  EXPECT_THAT(c.err, HasSubstr("polydual: warning: "));
  CmdResult quiet = run("info " + sheet + " --quiet");
  EXPECT_EQ(quiet.code, 0);
  EXPECT_EQ(quiet.err, "");
}

TEST(CliOptions, VtuEncodingAndCompression) {
  const std::string in = meshes().msh.string();
  const fs::path d = scratch_root();
  struct Case {
    const char* opts;
    const char* file;
    const char* marker;
  };
  // The default is appended raw binary.
  const Case cases[] = {{"", "e_default.vtu", "<AppendedData encoding=\"raw\">"},
                        {"--vtu-encoding base64", "e_b64.vtu", "format=\"binary\""},
                        {"--vtu-encoding raw", "e_raw.vtu", "<AppendedData encoding=\"raw\">"},
                        {"--vtu-encoding ascii", "e_ascii.vtu", "format=\"ascii\""},
                        {"--zlib 6", "e_zlib.vtu", "compressor=\"vtkZLibDataCompressor\""}};
  std::string cells;
  for (const Case& k : cases) {
    CmdResult r = run("convert " + in + " -o " + (d / k.file).string() + " --optimize none " + k.opts);
    ASSERT_EQ(r.code, 0) << k.opts << r.err;
    EXPECT_THAT(slurp(d / k.file), HasSubstr(k.marker)) << k.opts;
    CmdResult chk = run("check " + (d / k.file).string() + " --json");
    ASSERT_EQ(chk.code, 0) << k.opts << chk.err;
    if (cells.empty()) cells = jq(chk.out, "d['cells']");
    EXPECT_EQ(jq(chk.out, "d['cells']"), cells) << k.opts;
  }
  EXPECT_LT(fs::file_size(d / "e_zlib.vtu"), fs::file_size(d / "e_b64.vtu"));
  EXPECT_EQ(slurp(d / "e_default.vtu"), slurp(d / "e_raw.vtu"));
  EXPECT_EQ(run("convert " + in + " -o " + (d / "e_bad.vtu").string() + " --zlib 6 --vtu-encoding ascii").code, 2);
}

TEST(CliOptions, ForceAndOutputGuard) {
  const std::string in = meshes().msh.string();
  const fs::path d = scratch_root() / "guard";
  fs::create_directories(d / "mine");
  std::ofstream(d / "mine/notes.txt") << "user data";
  // A directory that is not a case is refused without --force, untouched.
  CmdResult r = run("convert " + in + " -o " + (d / "mine").string() + " --optimize none");
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(fs::exists(d / "mine/constant"));
  ASSERT_EQ(run("convert " + in + " -o " + (d / "mine").string() + " --optimize none --force").code, 0);
  EXPECT_TRUE(fs::exists(d / "mine/constant/polyMesh/owner"));
  EXPECT_EQ(slurp(d / "mine/notes.txt"), "user data");
  // The input is never the output.
  EXPECT_EQ(run("convert " + in + " -o " + in + " --format vtu --force").code, 2);
  EXPECT_TRUE(fs::exists(in));
}

TEST(CliOptions, SplitByDefaultNoSplitRoundsAndRequireValid) {
  const std::string off = convert_json("--optimize none --no-split", "s_off.vtu");
  const std::string on = convert_json("--optimize none", "s_on.vtu");
  const std::string zero = convert_json("--optimize none --split-rounds 0", "s_zero.vtu");
  ASSERT_GT(jnum(off, "d['invalid_after']"), 0);
  EXPECT_EQ(jq(off, "'split' in d['seconds']['stages']"), "False");
  EXPECT_EQ(jq(off, "d['split'] is None"), "True");
  EXPECT_EQ(jq(on, "'split' in d['seconds']['stages']"), "True");
  // By default the rounds run until every cell is valid (whole cuts).
  EXPECT_GT(jnum(on, "len(d['split']['rounds'])"), 0);
  EXPECT_EQ(jnum(on, "d['invalid_after']"), 0);
  // The vertices of the invalid cells are made whole; without an optimiser
  // the coarsening starts from one cell per side (CoarsenStart::TopDown),
  // and on this mesh every such cell is valid: no cell is added.
  EXPECT_GE(jnum(on, "d['split']['vertices_whole']"), jnum(off, "d['invalid_after']"));
  EXPECT_EQ(jnum(on, "d['cells']"), jnum(off, "d['cells']"));
  EXPECT_EQ(jnum(on, "d['split']['cells_split']['still_invalid']"), jnum(on, "d['invalid_after']"));
  // No rounds: the first dual as it is (no free edge in this mesh).
  EXPECT_EQ(jnum(zero, "len(d['split']['rounds'])"), 0);
  EXPECT_EQ(jnum(zero, "d['invalid_after']"), jnum(off, "d['invalid_after']"));
  EXPECT_EQ(run("convert " + meshes().msh.string() + " -o " + (scratch_root() / "s_bad.vtu").string() +
                " --split-rounds " + std::to_string(polydual::SplitParams::kMaxRounds + 1))
                .code,
            2);
  // --require-valid: exit 1, every invalid cell named, nothing written.
  const fs::path out = scratch_root() / "s_req.vtu";
  const CmdResult r = run("convert " + meshes().msh.string() + " -o " + out.string() +
                          " --optimize none --split-rounds 0 --require-valid");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("remain invalid"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("class dim"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(run("convert " + meshes().msh.string() + " -o " + out.string() + " --require-valid").code, 0);
  EXPECT_TRUE(fs::exists(out));
}
