// Feature inference (design §3; proofs/classification.md L15): sharp edges in
// consistent chains are features, isolated and zigzag ones on a coarse curved
// surface are not. The rule on hand-made edge lists, then on meshes made at
// test time by TetGen (CAD-like PLCs, Gmsh's STL of OpenCASCADE models: a box,
// a cylinder, a coarse sphere, a box with a round hole) and, when the
// generator of experiments/meshgen is built, by CGAL Mesh_3 from a labelled
// image. A missing tool skips its test.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "classify/classify.h"
#include "classify/features.h"
#include "io/read_tet_mesh.h"
#include "require_tool.h"
#include "run_command.h"

using namespace polydual;

namespace {

namespace fs = std::filesystem;

// ---- the rule on edge lists

const Vec3 kUp{0, 0, 1}, kSouth{0, -1, 0}, kEast{1, 0, 0};

// An edge along +x from vertex a to a+1 between a flat top (left, +z) and a
// side facing -y (right), i.e. a box's 90-degree edge; `bend` overrides the
// reported angle, `tilt` turns the side's normal about the edge's direction.
BendEdge box_edge(std::uint32_t a, double bend, double tilt_deg = 0) {
  const double t = tilt_deg * M_PI / 180;
  return BendEdge{a, a + 1, kEast, kUp, Vec3{0, -std::cos(t), std::sin(t)}, bend};
}

using V = FeatureVerdict;

TEST(ClassifyFeatures, ConsistentChainIsAFeatureIsolatedEdgeIsNot) {
  FeatureRule rule;  // 30 / 60 / 3
  // Four collinear 45-degree edges with the same two sides: a feature line.
  std::vector<BendEdge> line;
  for (std::uint32_t i = 0; i < 4; ++i) line.push_back(box_edge(i, 45));
  EXPECT_THAT(select_feature_edges(line, rule), ::testing::Each(V::Chain));
  // Two such edges alone: too short, and nothing to join.
  line.resize(2);
  EXPECT_THAT(select_feature_edges(line, rule), ::testing::Each(V::Noise));
  // One edge at 20 degrees: smooth.
  EXPECT_EQ(select_feature_edges({box_edge(0, 20)}, rule), std::vector<V>{V::Smooth});
  // An isolated strong edge (a fold of one edge) is noise; two linked ones are kept.
  EXPECT_EQ(select_feature_edges({box_edge(0, 90)}, rule), std::vector<V>{V::Noise});
  EXPECT_EQ(select_feature_edges({box_edge(0, 90), box_edge(1, 90)}, rule), (std::vector<V>{V::Strong, V::Strong}));
}

// A zigzag: every other edge has its sides swapped (the bend changes sign), so
// no two edges continue one line, however long the run.
TEST(ClassifyFeatures, ZigzagIsNoise) {
  std::vector<BendEdge> zig;
  for (std::uint32_t i = 0; i < 6; ++i) {
    BendEdge e = box_edge(i, 45);
    if (i % 2) std::swap(e.left, e.right);
    zig.push_back(e);
  }
  EXPECT_THAT(select_feature_edges(zig, FeatureRule{}), ::testing::Each(V::Noise));
  // Sides that twist by more than the feature angle (plus the line's turn, 0
  // here) from one edge to the next: no line either.
  std::vector<BendEdge> twist;
  for (std::uint32_t i = 0; i < 6; ++i) twist.push_back(box_edge(i, 45, (i % 2) * 40.0));
  EXPECT_THAT(select_feature_edges(twist, FeatureRule{}), ::testing::Each(V::Noise));
  // The same twist of 25 degrees stays one line.
  std::vector<BendEdge> mild;
  for (std::uint32_t i = 0; i < 6; ++i) mild.push_back(box_edge(i, 45, (i % 2) * 25.0));
  EXPECT_THAT(select_feature_edges(mild, FeatureRule{}), ::testing::Each(V::Chain));
}

// Three strong single edges meeting at a corner whose other edges are flat (a
// coarse box's corner): each edge is kept, though none links to another.
TEST(ClassifyFeatures, SingleEdgesBetweenFlatCornersAreKept) {
  // Vertices 0 (corner) .. 3; edges 0-1, 0-2, 0-3 at 90 degrees with unrelated
  // sides; 1, 2, 3 are corners too (each with two more strong edges to 4..9),
  // and every corner has a flat edge.
  std::vector<BendEdge> edges;
  auto strong = [&](std::uint32_t a, std::uint32_t b, Vec3 d) { edges.push_back(BendEdge{a, b, d, kUp, kSouth, 90}); };
  strong(0, 1, kEast);
  strong(0, 2, Vec3{0, 1, 0});
  strong(0, 3, kUp);
  for (std::uint32_t c = 1; c <= 3; ++c) {
    strong(c, 3 + 2 * c, kEast);
    strong(c, 4 + 2 * c, kUp);
  }
  for (std::uint32_t c = 0; c <= 3; ++c) edges.push_back(BendEdge{c, 100 + c, kEast, kUp, kUp, 0});
  const auto v = select_feature_edges(edges, FeatureRule{});
  EXPECT_EQ(v[0], V::Strong);
  EXPECT_EQ(v[1], V::Strong);
  EXPECT_EQ(v[2], V::Strong);
  // The same corner on a crumpled background (a smooth edge bending 25 degrees at it) is no anchor.
  edges[edges.size() - 4].bend = 25;
  EXPECT_EQ(select_feature_edges(edges, FeatureRule{})[0], V::Noise);
}

// ---- meshes made at test time

using test::have_command;

// A directory of this process, removed at exit.
const fs::path& scratch() {
  struct Dir {
    fs::path path = fs::temp_directory_path() / ("polydual_classify_features_" + std::to_string(getpid()));
    Dir() { fs::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

std::string write(const std::string& name, const std::string& text) {
  const fs::path p = scratch() / name;
  std::ofstream(p) << text;
  return p.string();
}

void run(const std::string& cmd) {
  int code = 0;
  const std::string out = polydual::testing::capture("cd " + scratch().string() + " && " + cmd + " 2>&1", code);
  ASSERT_EQ(code, 0) << cmd << "\n" << out;
}

// TetGen (-p, plus `quality`) on a PLC or STL written to `name`; the mesh read back.
ClassifiedTetMesh tetgen(const std::string& name, const std::string& quality = "") {
  run("tetgen -p" + quality + " " + name + " > " + name + ".log");
  const std::string stem = name.substr(0, name.rfind('.'));
  return classify(read_tet_mesh((scratch() / (stem + ".1.node")).string()));
}

// Gmsh's surface mesh of an OpenCASCADE model as STL (the model's faces and
// edges are lost: only triangles), then TetGen.
ClassifiedTetMesh occ_stl(const std::string& name, const std::string& body, double size) {
  const std::string geo = write(name + ".geo", "SetFactory(\"OpenCASCADE\");\n" + body +
                                                   "\nMesh.MeshSizeMax = " + std::to_string(size) +
                                                   ";\nMesh.MeshSizeMin = " + std::to_string(size) + ";\n");
  run("gmsh -2 " + geo + " -format stl -o " + name + ".stl > " + name + ".gmsh.log");
  return tetgen(name + ".stl");
}

struct Counts {
  std::size_t vertices, edges, faces;
  bool operator==(const Counts&) const = default;
};
Counts counts(const ClassifiedTetMesh& m) { return {m.model().count(0), m.model().count(1), m.model().count(2)}; }
std::ostream& operator<<(std::ostream& o, const Counts& c) {
  return o << c.vertices << " vertices, " << c.edges << " edges, " << c.faces << " faces";
}

std::size_t noise(const ClassifiedTetMesh& m) {
  std::size_t n = 0;
  for (const MarkerFeatures& f : m.marker_features()) n += f.noise_edges;
  return n;
}

// A unit cube with its edge x = z = 1 chamfered at 45 degrees: 10 corners,
// 15 edges, 7 facets, all under marker 1. The chamfer's bends (45 degrees)
// are below the strong angle: found as chains when TetGen subdivides them,
// and between the cube's corners when each is a single edge (-p alone).
constexpr const char* kChamferPoly =
    "10 3 0 0\n1 0 0 0\n2 1 0 0\n3 1 0 0.7\n4 0.7 0 1\n5 0 0 1\n6 0 1 0\n7 1 1 0\n8 1 1 0.7\n9 0.7 1 1\n"
    "10 0 1 1\n7 1\n1 0 1\n5 1 2 3 4 5\n1 0 1\n5 6 10 9 8 7\n1 0 1\n4 1 5 10 6\n1 0 1\n4 1 6 7 2\n"
    "1 0 1\n4 2 7 8 3\n1 0 1\n4 3 8 9 4\n1 0 1\n4 4 9 10 5\n0\n0\n";

TEST(ClassifyFeatures, TetgenChamferedCubeKeepsEveryEdge) {
  if (!have_command("tetgen")) POLYDUAL_MISSING_TOOL("tetgen is not installed (Debian package tetgen)");
  write("chamfer.poly", kChamferPoly);
  const ClassifiedTetMesh fine = tetgen("chamfer.poly", "q1.4a0.002");
  EXPECT_EQ(counts(fine), (Counts{10, 15, 7}));
  ASSERT_EQ(fine.marker_features().size(), 1u);
  EXPECT_GT(fine.marker_features()[0].chain_edges, 0u);  // the chamfer's 45-degree edges
  EXPECT_EQ(fine.marker_features()[0].model_faces, 7u);
  write("chamfer_coarse.poly", kChamferPoly);
  EXPECT_EQ(counts(tetgen("chamfer_coarse.poly")), (Counts{10, 15, 7}));
}

// `info` (text and --json) and the convert summary's model record list per marker what
// was split and why (coarse chamfered cube: 13 strong edges, the chamfer's
// two 45-degree edges kept as single edges between corners).
TEST(ClassifyFeatures, InfoAndConvertJsonReportPerMarker) {
  if (!have_command("tetgen")) POLYDUAL_MISSING_TOOL("tetgen is not installed (Debian package tetgen)");
  write("report.poly", kChamferPoly);
  run("tetgen -p report.poly > report.log");
  const std::string mesh = (scratch() / "report.1.node").string();
  for (const std::string& cmd :
       {"info " + mesh + " --json", "convert " + mesh + " -o " + (scratch() / "report.vtu").string() + " --json"}) {
    const auto r = polydual::testing::run_polydual(cmd);
    ASSERT_EQ(r.code, 0) << cmd << "\n" << r.out;
    const std::string one = "\"marker\": 1,\n        \"facets\": 16,\n        \"model_faces\": 7,\n"
                            "        \"model_edges\": 15,\n        \"corners\": 10,\n        \"sharp_edges\": 15,\n"
                            "        \"feature_edges_strong\": 13,\n        \"feature_edges_chain\": 2,\n"
                            "        \"noise_edges\": 0";
    EXPECT_THAT(r.out, ::testing::HasSubstr(one)) << cmd;
  }
  const auto text = polydual::testing::run_polydual("info " + mesh);
  EXPECT_THAT(text.out, ::testing::HasSubstr("marker 1: 16 triangles -> 7 faces, 15 edges, 10 corners; 15 sharp "
                                             "edges: 13 strong and 2 in feature lines kept, 0 dropped as noise"));
  const auto bad = polydual::testing::run_polydual("info " + mesh + " --strong-angle 0");
  EXPECT_EQ(bad.code, 2) << bad.out;
}

TEST(ClassifyFeatures, OccBoxFromStlHasItsTwelveEdges) {
  if (!have_command("gmsh") || !have_command("tetgen")) POLYDUAL_MISSING_TOOL("gmsh or tetgen is not installed");
  const ClassifiedTetMesh m = occ_stl("box", "Box(1) = {0,0,0, 1,0.7,0.4};", 0.3);
  EXPECT_EQ(counts(m), (Counts{8, 12, 6}));
}

// The rims are found (two closed model edges), the side stays one face.
TEST(ClassifyFeatures, OccCylinderFromStlHasItsRimsAndOneSide) {
  if (!have_command("gmsh") || !have_command("tetgen")) POLYDUAL_MISSING_TOOL("gmsh or tetgen is not installed");
  const ClassifiedTetMesh m = occ_stl("cylinder", "Cylinder(1) = {0,0,0, 0,0,1, 0.5};", 0.25);
  EXPECT_EQ(counts(m), (Counts{0, 2, 3}));
  for (const ModelEntity& e : m.model().entities[1]) EXPECT_EQ(e.bounds.size(), 2u) << "edge " << e.tag;
}

// A coarse sphere (32 to 121 tets) bends by more than 30 degrees at many
// edges, in no line: one face, no model edge or vertex.
TEST(ClassifyFeatures, CoarseOccSphereStaysOneFace) {
  if (!have_command("gmsh") || !have_command("tetgen")) POLYDUAL_MISSING_TOOL("gmsh or tetgen is not installed");
  std::size_t dropped = 0;
  for (double size : {0.6, 0.8, 1.2}) {
    const ClassifiedTetMesh m = occ_stl("sphere" + std::to_string(int(size * 10)), "Sphere(1) = {0,0,0, 1};", size);
    EXPECT_EQ(counts(m), (Counts{0, 0, 1})) << "size " << size;
    dropped += noise(m);
  }
  EXPECT_GT(dropped, 20u);  // sharp edges were there, and judged noise
}

// A box with a round hole through it: the hole's rims are features although
// the hole's side turns by about 40 degrees from one rim edge to the next.
TEST(ClassifyFeatures, OccHoledBoxFromStlKeepsTheHole) {
  if (!have_command("gmsh") || !have_command("tetgen")) POLYDUAL_MISSING_TOOL("gmsh or tetgen is not installed");
  const ClassifiedTetMesh m = occ_stl("holed",
                                      "Box(1) = {0,0,0, 1,1,0.5};\nCylinder(2) = {0.5,0.5,-0.1, 0,0,0.7, 0.2};\n"
                                      "BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };",
                                      0.15);
  EXPECT_EQ(counts(m), (Counts{8, 14, 7}));
}

// CGAL Mesh_3 of a labelled image (experiments/meshgen): a slab with two
// blocks on it, whose faces Mesh_3 rounds and crumples (no feature
// protection). The flat interfaces stay one face each, and the whole model
// has a few faces, not the hundreds that every sharp edge made.
std::string labelled_image_generator() {
  if (const char* env = std::getenv("POLYDUAL_LABELLED_IMAGE_MEDIT")) return env;
#ifdef POLYDUAL_LABELLED_IMAGE_MEDIT
  return POLYDUAL_LABELLED_IMAGE_MEDIT;
#else
  return "";
#endif
}

TEST(ClassifyFeatures, Mesh3LabelledImageKeepsSmoothPatchesWhole) {
  const std::string gen = labelled_image_generator();
  if (gen.empty() || !fs::exists(gen))
    POLYDUAL_MISSING_TOOL("labelled_image_medit not built (cmake -DPOLYDUAL_BUILD_MESHGEN=ON, or set "
                          "POLYDUAL_LABELLED_IMAGE_MEDIT)");
  run(gen + " blocks.mesh shape=blocks n=64 facet_size=0.04 cell_size=0.04 > gen.log");
  const ClassifiedTetMesh m = classify(read_tet_mesh((scratch() / "blocks.mesh").string()));
  EXPECT_LE(m.model().count(2), 12u);
  EXPECT_LE(m.model().count(1), 12u);
  std::size_t sharp = 0;
  for (const MarkerFeatures& f : m.marker_features()) {
    ASSERT_TRUE(f.marker.has_value());
    sharp += f.sharp_edges;
    // Markers 2 and 3: the flat bottoms of the blocks (1|2, 1|3).
    if (*f.marker == 2 || *f.marker == 3) EXPECT_EQ(f.model_faces, 1u) << "marker " << *f.marker;
    EXPECT_EQ(f.sharp_edges, f.strong_edges + f.chain_edges + f.noise_edges);
  }
  EXPECT_GT(sharp, 300u);
  EXPECT_GT(noise(m), sharp / 2);
}

}  // namespace
