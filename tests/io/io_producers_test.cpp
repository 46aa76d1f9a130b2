// Files as other producers write them, which Gmsh's own conventions would
// refuse: Netgen's "Gmsh2 Format" export (msh 2.0 spelt "2.000000", every tet
// negatively oriented), meshes of the other orientation convention (flipped
// whole; mixed orientations and degenerate tets stay errors), Gmsh meshes that
// carry homology and cohomology chains (dropped: results, not model), and
// files that hold no tetrahedra. Netgen and Gmsh are run at test time when
// installed (skipped otherwise); the committed Netgen file is read always.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "classify/classify.h"
#include "core/error.h"
#include "generate/random_mesh.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"
#include "io/read_tet_mesh.h"
#include "io/vtu_reader.h"
#include "mesh/validate.h"
#include "pipeline/convert.h"
#include "require_tool.h"
#include "run_command.h"

namespace polydual {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

const std::string kNetgenFile = std::string(POLYDUAL_TEST_DATA) + "/netgen/holed_box_gmsh2.msh";
constexpr std::size_t kNetgenTets = 1150;  // tets in kNetgenFile
const std::string kFlipped = "negatively oriented (the producer's convention): flipped";

struct ScratchDir {
  fs::path path = fs::path(::testing::TempDir()) / ("polydual_producers_" + std::to_string(getpid()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() { fs::remove_all(path); }
};
const fs::path& scratch() {
  static const ScratchDir dir;
  return dir.path;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
std::string write(const std::string& name, const std::string& bytes) {
  const std::string path = (scratch() / name).string();
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::size_t count_containing(const std::vector<std::string>& lines, const std::string& part) {
  return std::count_if(lines.begin(), lines.end(), [&](const std::string& w) { return w.find(part) != std::string::npos; });
}

// The tets selected by `pick` with two vertices swapped (i, j: which two).
TetSoup with_flipped(TetSoup s, const std::function<bool(std::size_t)>& pick, int i = 0, int j = 1) {
  for (std::size_t t = 0; t < s.tets.size(); ++t)
    if (pick(t)) std::swap(s.tets[t][i], s.tets[t][j]);
  return s;
}
const auto kAll = [](std::size_t) { return true; };

std::vector<double> sorted_cell_volumes(const PolyMesh& m) {
  std::vector<double> v(m.num_cells());
  for (std::size_t c = 0; c < v.size(); ++c) v[c] = cell_volume(m, CellId(c));
  std::sort(v.begin(), v.end());
  return v;
}

// The raw dual: no optimisation of the tets or the dual, no split (their
// choices may depend on the order of a tet's vertices, which a flip changes).
PipelineParams raw_dual() {
  PipelineParams p;
  p.optim.method = OptimParams::Method::None;
  p.split.enabled = false;
  p.tetopt.enabled = false;
  return p;
}

// The dual of `negative` (every tet flipped by the test) is the dual of
// `positive`: the same cells with the same volumes, one flip warning.
void expect_same_dual(const TetSoup& positive, const TetSoup& negative, double rel_tol,
                      const PipelineParams& params = {}) {
  const ConvertResult want = convert(positive, params);
  const ConvertResult got = convert(negative, params);
  EXPECT_EQ(count_containing(want.warnings, kFlipped), 0u);
  EXPECT_EQ(count_containing(got.warnings, "all " + std::to_string(negative.tets.size()) + " tets are " + kFlipped), 1u);
  ASSERT_EQ(got.mesh.num_cells(), want.mesh.num_cells());
  EXPECT_EQ(got.mesh.num_faces(), want.mesh.num_faces());
  EXPECT_EQ(got.report.invalid_before, want.report.invalid_before);
  EXPECT_EQ(got.report.invalid_after, want.report.invalid_after);
  EXPECT_EQ(got.check.validation.defects().size(), want.check.validation.defects().size());
  const std::vector<double> a = sorted_cell_volumes(want.mesh), b = sorted_cell_volumes(got.mesh);
  for (std::size_t c = 0; c < a.size(); ++c)
    EXPECT_NEAR(b[c], a[c], rel_tol * std::fabs(a[c])) << "cell volume rank " << c;
  const auto& va = want.check.validation.material_volume;
  const auto& vb = got.check.validation.material_volume;
  ASSERT_EQ(vb.size(), va.size());
  for (const auto& [tag, v] : va) EXPECT_NEAR(vb.at(tag), v, 1e-12 * v) << "material " << tag;
  for (const auto& [tag, v] : want.check.validation.primal_material_volume)
    EXPECT_NEAR(got.check.validation.primal_material_volume.at(tag), v, 1e-12 * v) << "material " << tag;
}

// ---- Netgen's msh 2.0 export

TEST(IoProducers, NetgenGmsh2ExportIsReadAndFlipped) {
  const TetSoup s = read_tet_mesh(kNetgenFile);
  EXPECT_EQ(s.tets.size(), kNetgenTets);
  EXPECT_EQ(s.points.size(), 335u);
  EXPECT_EQ(s.triangles.size(), 510u);  // boundary triangles, tagged by Netgen's boundary conditions 1..7
  EXPECT_TRUE(s.warnings.empty());
  const ClassifiedTetMesh m = classify(s);
  ASSERT_EQ(m.classification_warnings().size(), 1u);
  EXPECT_EQ(m.classification_warnings()[0], kNetgenFile + ": all 1150 tets are " + kFlipped);
  EXPECT_EQ(m.num_tets(), kNetgenTets);
  EXPECT_EQ(m.model().count(2), 7u);  // 6 box sides and the hole
  EXPECT_EQ(m.model().count(1), 14u);  // 12 box edges and the hole's two circles
  // Under the name Netgen proposes for the export.
  const std::string gmsh2 = write("holed_box.gmsh2", slurp(kNetgenFile));
  EXPECT_EQ(read_tet_mesh(gmsh2).tets.size(), kNetgenTets);
}

TEST(IoProducers, NetgenDualIsTheDualOfTheFlippedMesh) {
  const TetSoup negative = read_tet_mesh(kNetgenFile);
  // Swapping the same two vertices as classify() does gives the same tets,
  // so the whole default pipeline gives the same result; swapping others
  // gives the same raw dual.
  expect_same_dual(with_flipped(negative, kAll, 2, 3), negative, 0.0);
  expect_same_dual(with_flipped(negative, kAll, 0, 1), negative, 1e-9, raw_dual());
}

TEST(IoProducers, ConvertJsonAndStderrCarryTheFlipWarning) {
  const std::string out = (scratch() / "netgen.vtu").string(), err = (scratch() / "netgen.err").string();
  int code = 0;
  const std::string json =
      testing::capture(std::string(POLYDUAL_BINARY) + " convert " + kNetgenFile + " -o " + out + " --json 2>" + err, code);
  EXPECT_EQ(code, 0);
  const std::string line = kNetgenFile + ": all 1150 tets are " + kFlipped;
  EXPECT_THAT(json, HasSubstr("\"warnings\": [\n    \"" + line + "\"")) << json.substr(0, 2000);
  EXPECT_THAT(slurp(err), HasSubstr("polydual: warning: " + line + "\n"));
  EXPECT_TRUE(fs::exists(out));
}

TEST(IoProducers, NetgenRunAtTestTime) {
  if (!test::have_python_module("netgen.csg")) POLYDUAL_MISSING_TOOL("python3-netgen is not installed");
  const std::string out = (scratch() / "netgen_now.msh").string();
  const std::string cmd = "/usr/bin/python3 " + std::string(POLYDUAL_TEST_DATA) + "/netgen/make_gmsh2.py " + out +
                          " 0.35 > " + out + ".log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_THAT(slurp(out).substr(0, 30), HasSubstr("$MeshFormat\n2.000000 0 8\n"));
  const TetSoup negative = read_msh_file(out);
  EXPECT_GT(negative.tets.size(), kNetgenTets);  // a finer mesh than the committed one
  expect_same_dual(with_flipped(negative, kAll, 2, 3), negative, 0.0);
  expect_same_dual(with_flipped(negative, kAll, 0, 1), negative, 1e-9, raw_dual());
}

// ---- msh 2.0 / 2.1 / 2.2 however the version is spelt

const std::string kNodes = "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n$EndNodes\n";
// Two tets sharing triangle (2, 3, 4), in Netgen's orientation and tags.
const std::string kNegativeTets = "$Elements\n3\n1 2 2 3 3  2 3 4\n2 4 2 100001 100001  1 3 2 4\n"
                                  "3 4 2 100001 100001  5 2 3 4\n$EndElements\n";

std::string msh_of_version(const std::string& version, const std::string& rest = kNodes + kNegativeTets) {
  return "$MeshFormat\n" + version + " 0 8\n$EndMeshFormat\n" + rest;
}

TEST(IoProducers, Msh2VersionSpellings) {
  for (const char* v : {"2", "2.0", "2.000000", "2.1", "2.10", "2.2", "2.20", "4.1"}) {
    SCOPED_TRACE(v);
    if (std::string(v) == "4.1") {
      const std::string m4 = msh_of_version(v, "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                                "$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n");
      EXPECT_EQ(read_msh(m4, "t.msh").tets.size(), 1u);
      continue;
    }
    const TetSoup s = read_msh(msh_of_version(v), "t.msh");
    ASSERT_EQ(s.tets.size(), 2u);
    EXPECT_EQ(s.tet_region[0], 100001);
    EXPECT_EQ(s.triangles.size(), 1u);
  }
  for (const char* v : {"2.3", "3", "1", "4", "4.0", "2.05", "2.2.1", "2.2x", "22", ".2", "two", "-2"}) {
    SCOPED_TRACE(v);
    EXPECT_THAT(error_of([&] { read_msh(msh_of_version(v), "t.msh"); }),
                HasSubstr("t.msh: line 2: msh format version '" + std::string(v) + "' not supported (use 2.2 or 4.1)"));
  }
}

TEST(IoProducers, Msh20PhysicalNamesHaveNoDimension) {
  const std::string names = "$PhysicalNames\n3\n100001 \"steel\"\n3 \"inlet\"\n77 \"unused\"\n$EndPhysicalNames\n";
  const TetSoup s = read_msh(msh_of_version("2.000000", names + kNodes + kNegativeTets), "t.msh");
  ASSERT_EQ(s.groups.size(), 2u);  // a dimensionless name names the groups of its tag that elements use
  EXPECT_EQ(s.groups[0].dim, 2);
  EXPECT_EQ(s.groups[0].name, "inlet");
  EXPECT_EQ(s.groups[1].dim, 3);
  EXPECT_EQ(s.groups[1].name, "steel");
  EXPECT_EQ(s.groups[1].entities, std::vector<std::int32_t>{100001});
  // 2.0 with the 2.1 layout (dimension first) is read as well.
  const TetSoup t = read_msh(msh_of_version("2.0", "$PhysicalNames\n1\n3 100001 \"steel\"\n$EndPhysicalNames\n" +
                                                       kNodes + kNegativeTets), "t.msh");
  ASSERT_EQ(t.groups.size(), 2u);
  EXPECT_EQ(t.groups[1].name, "steel");
  // From 2.1 on the dimension is required.
  EXPECT_THAT(error_of([&] { read_msh(msh_of_version("2.2", names + kNodes + kNegativeTets), "t.msh"); }),
              HasSubstr("t.msh: line 6: physical dimension 100001 out of range (0..3)"));
}

// Binary msh 2.0 (Gmsh's homology module writes 2.0 files; the layout is 2.2's).
TEST(IoProducers, BinaryMsh20) {
  std::string b = "$MeshFormat\n2 1 8\n";
  auto put = [&](auto v) { b.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(int(1));
  b += "\n$EndMeshFormat\n$Nodes\n5\n";
  const double xyz[5][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  for (int i = 0; i < 5; ++i) {
    put(int(i + 1));
    for (double x : xyz[i]) put(x);
  }
  b += "\n$EndNodes\n$Elements\n2\n";
  for (int v : {4, 2, 2}) put(v);  // type 4 (tet), 2 elements, 2 tags
  for (int v : {1, 100001, 100001, 1, 3, 2, 4, 2, 100001, 100001, 5, 2, 3, 4}) put(v);
  b += "\n$EndElements\n";
  const TetSoup s = read_msh(b, "t.msh");
  ASSERT_EQ(s.tets.size(), 2u);
  const ClassifiedTetMesh m = classify(s);
  EXPECT_EQ(m.classification_warnings(), std::vector<std::string>{"t.msh: all 2 tets are " + kFlipped});
}

// ---- orientation: all negative is flipped, mixed and degenerate are errors

TEST(IoProducers, AllNegativeMeshesGiveTheSameDual) {
  const TetSoup kuhn = kuhn_lattice(4, 2, 2, 1.0, 0.5, 0.75, 2);
  expect_same_dual(kuhn, with_flipped(kuhn, kAll, 3, 2), 0.0);
  expect_same_dual(kuhn, with_flipped(kuhn, kAll), 1e-9, raw_dual());
  RandomMeshParams p;
  p.seed = 7;
  p.num_points = 60;
  p.regions = 2;
  p.fracture = true;
  const TetSoup random = random_classified_mesh(p);
  // (The default pipeline optimises fracture meshes for seconds: the raw dual.)
  expect_same_dual(random, with_flipped(random, kAll, 2, 3), 0.0, raw_dual());
  expect_same_dual(random, with_flipped(random, kAll, 1, 3), 1e-9, raw_dual());
}

TEST(IoProducers, OneTetMeshOfTheOtherOrientation) {
  TetSoup s = kuhn_lattice(1, 1, 1);
  s.tets.resize(1);
  s.tet_region.resize(1);
  const ClassifiedTetMesh m = classify(with_flipped(s, kAll));
  EXPECT_EQ(m.classification_warnings(), std::vector<std::string>{s.source + ": all 1 tet is " + kFlipped});
}

TEST(IoProducers, MixedOrientationsNameTheInvertedTets) {
  const TetSoup kuhn = kuhn_lattice(3, 3, 3);  // 162 tets
  const auto in = [](std::initializer_list<std::size_t> l) {
    return [l](std::size_t t) { return std::find(l.begin(), l.end(), t) != l.end(); };
  };
  EXPECT_THAT(error_of([&] { classify(with_flipped(kuhn, in({9}))); }),
              HasSubstr(": tet 10: tet 10 is inverted (negative orientation)"));
  EXPECT_THAT(error_of([&] { classify(with_flipped(kuhn, in({40, 2, 99}))); }),
              HasSubstr(": tet 3: 3 of 162 tets are inverted (negative orientation, against the other 159): "
                        "tets 3, 41, 100; a mesh must orient all its tets the same way"));
  // Mostly negative: the positive ones are the odd ones out.
  EXPECT_THAT(error_of([&] { classify(with_flipped(kuhn, [](std::size_t t) { return t != 5; })); }),
              HasSubstr(": tet 6: 1 of 162 tets is inverted (positive orientation, against the other 161, "
                        "negative ones): tet 6;"));
  // Many: the first ten are named.
  EXPECT_THAT(error_of([&] { classify(with_flipped(kuhn, [](std::size_t t) { return t % 3 == 0; })); }),
              HasSubstr("54 of 162 tets are inverted (negative orientation, against the other 108): "
                        "tets 1, 4, 7, 10, 13, 16, 19, 22, 25, 28 and 44 more;"));
}

TEST(IoProducers, DegenerateTetStaysAnErrorInANegativeMesh) {
  TetSoup s = with_flipped(kuhn_lattice(2, 2, 2), kAll);
  // Four corners of the bottom face: coplanar, a zero-volume tet.
  const auto corner = [&](double x, double y) {
    for (std::uint32_t v = 0; v < s.points.size(); ++v)
      if (s.points[v] == Point3{x, y, 0}) return v;
    return std::uint32_t(-1);
  };
  s.tets.push_back({corner(0, 0), corner(2, 0), corner(0, 2), corner(2, 2)});
  s.tet_region.push_back(1);
  EXPECT_THAT(error_of([&] { classify(s); }), HasSubstr(": tet 49: tet 49 has zero volume (degenerate)"));
}

// ---- Gmsh's homology and cohomology chains

bool have_gmsh() {
  static const bool have = test::have_command("gmsh");
  return have;
}

// A box with a square hole through it (first Betti number 1), its whole
// boundary a physical surface; with `chains`, Gmsh's solver adds its chains:
// 1-cycles and 1-cocycles (curves), relative 2- and 3-chains (surfaces, and
// tets overlapping the mesh) and 0-chains (points).
std::string holed_box_geo(bool chains) {
  std::string geo =
      "SetFactory(\"OpenCASCADE\");\nBox(1) = {0,0,0, 3,3,1};\nBox(2) = {1,1,0, 1,1,1};\n"
      "BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }\nMesh.MeshSizeMax = 0.6;\n"
      "Physical Volume(\"body\") = {1};\nPhysical Surface(\"skin\") = Abs(Boundary{ Volume{1}; });\n";
  if (chains)
    geo += "Homology(1) {{1},{}};\nCohomology(1) {{1},{}};\nHomology(2) {{1},{2}};\nHomology(3) {{1},{2}};\n"
           "Cohomology(0) {{1},{}};\n";
  return geo;
}

std::string gmsh_mesh(const std::string& name, const std::string& geo, const std::string& options) {
  const std::string g = write(name + ".geo", geo), out = (scratch() / (name + ".msh")).string();
  const std::string cmd = "gmsh -3 " + g + " " + options + " -o " + out + " > " + out + ".log 2>&1";
  if (std::system(cmd.c_str()) != 0) ADD_FAILURE() << "failed: " << cmd;
  return out;
}

// The chain groups Gmsh wrote in $PhysicalNames.
std::vector<std::string> chain_names_in(const std::string& path) {
  std::vector<std::string> out;
  std::istringstream in(slurp(path));
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t q = line.find("\"H");
    if (q != std::string::npos && (line[q + 2] == '_' || line[q + 2] == '^'))
      out.push_back(line.substr(q + 1, line.rfind('"') - q - 1));
  }
  return out;
}

struct Model {
  std::size_t tets, faces, edges, vertices;
  bool operator==(const Model&) const = default;
};
std::ostream& operator<<(std::ostream& os, const Model& m) {
  return os << m.tets << " tets, " << m.faces << " faces, " << m.edges << " edges, " << m.vertices << " vertices";
}
Model model_of(const TetSoup& s) {
  const ClassifiedTetMesh m = classify(s);
  return {m.num_tets(), m.model().count(2), m.model().count(1), m.model().count(0)};
}

TEST(IoProducers, GmshHomologyChainsAreDropped) {
  if (!have_gmsh()) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  for (const char* options : {"-format msh4", "-format msh4 -save_all", "-format msh4 -bin", "-format msh2",
                              "-format msh2 -bin"}) {
    SCOPED_TRACE(options);
    std::string tag = options;
    std::replace(tag.begin(), tag.end(), ' ', '_');
    const std::string with = gmsh_mesh("chains" + tag, holed_box_geo(true), options);
    const std::string without = gmsh_mesh("plain" + tag, holed_box_geo(false), options);
    const std::vector<std::string> chains = chain_names_in(with);
    ASSERT_GE(chains.size(), 5u);  // H_1, H^1, H_2, H_3, H^0 at least
    const TetSoup s = read_msh_file(with), plain = read_msh_file(without);
    EXPECT_EQ(s.ignored.chains, chains.size());
    EXPECT_EQ(plain.ignored.chains, 0u);
    EXPECT_EQ(s.tets.size(), plain.tets.size());  // the 3-chain's copies of the tets are gone
    EXPECT_GE(s.ignored.elements, plain.ignored.elements + s.tets.size());  // at least the 3-chain's tets
    EXPECT_EQ(count_containing(s.warnings, ": ignored " + std::to_string(chains.size()) +
                                               " homology and cohomology chains (" + chains[0]),
              1u);
    EXPECT_EQ(count_containing(s.warnings, "Gmsh's (co)homology results, not model entities"), 1u);
    for (const NamedGroup& g : s.groups) EXPECT_NE(g.name.substr(0, 2), "H_") << g.name;
    EXPECT_EQ(s.groups.size(), plain.groups.size());
    EXPECT_EQ(model_of(s), model_of(plain));
  }
}

// msh 2 with -save_all writes every element with physical tag 0: the chains
// cannot be found, and the reader says so.
TEST(IoProducers, GmshChainsInMsh2SaveAllAreNamedInAWarning) {
  if (!have_gmsh()) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  const std::string path = gmsh_mesh("chains_v2_save_all", holed_box_geo(true), "-format msh2 -save_all");
  const TetSoup s = read_msh_file(path);
  EXPECT_EQ(s.ignored.chains, 0u);
  EXPECT_EQ(count_containing(s.warnings, "names homology or cohomology chains (H"), 1u);
  EXPECT_EQ(count_containing(s.warnings, "that no element is in (msh 2 saved with -save_all)"), 1u);
}

// A chain written by hand in both formats, to pin the counts.
TEST(IoProducers, HandWrittenChainCounts) {
  const std::string names = "$PhysicalNames\n3\n1 7 \"H_1{1}1\"\n0 8 \"H^0{1}1\"\n3 1 \"body\"\n$EndPhysicalNames\n";
  const std::string nodes = "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n$EndNodes\n";
  const std::string elements = "$Elements\n6\n1 4 2 1 1 1 2 3 4\n2 4 2 1 1 5 3 2 4\n3 1 2 7 20 1 2\n4 1 2 7 20 2 5\n"
                               "5 15 2 8 21 1\n6 15 2 8 21 5\n$EndElements\n";
  const TetSoup s = read_msh(msh_of_version("2.2", names + nodes + elements), "t.msh");
  EXPECT_EQ(s.tets.size(), 2u);
  EXPECT_TRUE(s.edges.empty());
  EXPECT_TRUE(s.corners.empty());
  EXPECT_EQ(s.ignored.chains, 2u);
  EXPECT_EQ(s.ignored.curves, 1u);
  EXPECT_EQ(s.ignored.points, 1u);
  EXPECT_EQ(s.ignored.elements, 4u);
  ASSERT_EQ(s.groups.size(), 1u);
  EXPECT_EQ(s.groups[0].name, "body");
  EXPECT_EQ(s.warnings, std::vector<std::string>{"t.msh: ignored 2 homology and cohomology chains (H^0{1}1, H_1{1}1; "
                                                 "4 elements): Gmsh's (co)homology results, not model entities"});
  // A name that only looks alike is a model group.
  std::string like = names;
  like.replace(like.find("H_1{1}1"), 7, "H_inlet");
  const TetSoup t = read_msh(msh_of_version("2.2", like + nodes + elements), "t.msh");
  EXPECT_EQ(t.edges.size(), 2u);
  EXPECT_EQ(t.ignored.chains, 1u);
}

// ---- files that hold no tetrahedra, as Gmsh writes them

TEST(IoProducers, GmshEmptyModelHoldsNoTetrahedra) {
  if (!have_gmsh()) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)");
  for (const char* options : {"-format msh4", "-format msh2", "-format msh4 -bin"}) {
    SCOPED_TRACE(options);
    std::string tag = options;
    std::replace(tag.begin(), tag.end(), ' ', '_');
    const std::string empty = gmsh_mesh("empty" + tag, "", options);
    EXPECT_THAT(error_of([&] { read_msh_file(empty); }), HasSubstr(empty + ": "));
    EXPECT_THAT(error_of([&] { read_msh_file(empty); }), HasSubstr("the file holds no tetrahedra"));
    const std::string square =
        gmsh_mesh("square" + tag, "Point(1)={0,0,0};Point(2)={1,0,0};Point(3)={0,1,0};Line(1)={1,2};Line(2)={2,3};"
                                  "Line(3)={3,1};Curve Loop(1)={1,2,3};Plane Surface(1)={1};",
                  options);
    EXPECT_THAT(error_of([&] { read_msh_file(square); }),
                HasSubstr("the file holds no tetrahedra ($Elements has none, only "));
  }
}

// ---- the fuzzers' regression seeds (fuzz/regressions), replayed

// The reader a seed is for ('g' Gmsh, 'm' Medit, 'v' VTU, as the pipeline
// fuzzer's first byte), or 0 for the others (TetGen's three files in one,
// polyhedral VTUs).
char reader_of(const std::string& name, std::string& bytes) {
  auto starts = [&](const char* p) { return name.rfind(p, 0) == 0; };
  if (starts("msh_")) return 'g';
  if (starts("medit_")) return 'm';
  if (starts("vtu_") && !starts("vtu_poly_")) return 'v';
  if (starts("pipeline_") && !bytes.empty()) {
    const char c = bytes[0];
    bytes.erase(0, 1);
    return c == 'g' || c == 'm' || c == 'v' ? c : 0;
  }
  return 0;
}

// Every seed reads and classifies to a mesh or an InputError, nothing else;
// the seeds of the producers' files give what they were added for.
TEST(IoProducers, FuzzRegressionsReplay) {
  const fs::path dir = fs::path(POLYDUAL_SOURCE_DIR) / "fuzz" / "regressions";
  ASSERT_TRUE(fs::is_directory(dir)) << dir;
  std::map<std::string, std::string> outcome;  // seed -> warnings or error
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    std::string bytes = slurp(entry.path().string());
    const char reader = reader_of(name, bytes);
    if (!reader) continue;
    std::string& out = outcome[name];
    try {
      const TetSoup s = reader == 'g'   ? read_msh(bytes, name)
                        : reader == 'm' ? read_medit(bytes, name)
                                        : read_vtu(bytes, name);
      for (const std::string& w : s.warnings) out += w + "\n";
      const ClassifiedTetMesh m = classify(s);
      for (const std::string& w : m.classification_warnings()) out += w + "\n";
    } catch (const InputError& e) {
      out += std::string("error: ") + e.what();
    }
  }
  ASSERT_GE(outcome.size(), 20u) << "fewer regression seeds than committed in " << dir;
  EXPECT_THAT(outcome["msh_netgen_v2_000000_negative.msh"], HasSubstr("all 2 tets are " + kFlipped));
  EXPECT_THAT(outcome["pipeline_netgen_all_negative"], HasSubstr("all 2 tets are " + kFlipped));
  EXPECT_THAT(outcome["msh_v20_physical_names_without_dim.msh"], HasSubstr("all 1 tet is " + kFlipped));
  EXPECT_THAT(outcome["msh_homology_chains.msh"], HasSubstr("ignored 3 homology and cohomology chains (H^0{1}1, "
                                                            "H_1{1}1, H_3{1},{2}1; 6 elements, 1 volume)"));
  EXPECT_THAT(outcome["msh_homology_chains_save_all.msh"],
              HasSubstr("ignored 3 homology and cohomology chains (H_1{1}1, H^1{1}1, H_3{1},{2}1;"));
  EXPECT_EQ(outcome["msh_homology_chains_save_all.msh"].find("error"), std::string::npos);
  EXPECT_THAT(outcome["pipeline_mixed_orientation"], HasSubstr("tet 2 is inverted (negative orientation)"));
  for (const char* empty : {"msh_empty_model.msh", "medit_surface_only.mesh", "vtu_no_piece.vtu"})
    EXPECT_THAT(outcome[empty], HasSubstr(std::string("error: ") + empty + ": ")) << empty;
  EXPECT_THAT(outcome["msh_empty_model.msh"], HasSubstr("end of file: the file holds no tetrahedra (no $Nodes"));
  EXPECT_THAT(outcome["medit_surface_only.mesh"], HasSubstr("end of file: the file holds no tetrahedra (no Tetrahedra"));
  EXPECT_THAT(outcome["vtu_no_piece.vtu"], HasSubstr("line 1: the file holds no tetrahedra (no <Piece>"));
}

}  // namespace
}  // namespace polydual
