// The feature angle inside one face marker (design §3; proofs/classification.md
// L13): TetGen .face markers and Medit triangle refs that span sharp edges are
// split into model faces there, with model edges and vertices at the sharp
// edges and corners; each model face keeps its marker as source_tag (and the
// marker's name). The PLCs are tests/data/tetgen/*.poly, meshed by TetGen
// (tests/data/tetgen/make.sh); every facet has the one marker 1.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <set>
#include <string>

#include "classify/classify.h"
#include "exact_volume.h"
#include "dual/build_dual.h"
#include "generate/random_mesh.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"
#include "io/tetgen_io.h"

using namespace polydual;
using polydual::testing::exact_dual_volumes;
using polydual::testing::exact_primal_volumes;

namespace {

const std::string kData = std::string(POLYDUAL_TEST_DATA) + "/tetgen/";

struct Counts {
  std::size_t vertices, edges, faces, regions;
  bool operator==(const Counts&) const = default;
};
Counts counts(const ClassifiedTetMesh& m) {
  return {m.model().count(0), m.model().count(1), m.model().count(2), m.model().count(3)};
}
std::ostream& operator<<(std::ostream& o, const Counts& c) {
  return o << c.vertices << " vertices, " << c.edges << " edges, " << c.faces << " faces, " << c.regions << " regions";
}

// The exact volume identity per material: the dual's cells cover exactly the
// primal's tets of the same region. Returns the materials that differ.
std::set<std::int32_t> volume_mismatches(const ClassifiedTetMesh& m) {
  const PolyMesh pm = build_dual(m);
  const auto dual = exact_dual_volumes(pm), primal = exact_primal_volumes(m);
  std::set<std::int32_t> bad;
  for (const auto& [tag, q] : primal)
    if (!dual.count(tag) || !(dual.at(tag) == q)) bad.insert(tag);
  for (const auto& [tag, q] : dual)
    if (!primal.count(tag)) bad.insert(tag);
  return bad;
}

ClassifyParams angle(double deg) {
  ClassifyParams p;
  p.feature_angle_deg = deg;
  return p;
}

}  // namespace

// Two stacked boxes (two regions), one marker over all 11 facets: the corners,
// edges and faces of the PLC, and the interface between the boxes.
TEST(ClassifyMarkers, TetgenTwoBoxesOneMarker) {
  const TetSoup soup = read_tetgen_files(kData + "two_boxes.1.node");
  ASSERT_FALSE(soup.full_classification);
  ASSERT_FALSE(soup.triangles.empty());
  for (const TaggedTriangle& t : soup.triangles) ASSERT_EQ(t.tag, 1);
  const ClassifiedTetMesh m = classify(soup);
  EXPECT_EQ(counts(m), (Counts{16, 24, 12, 2}));
  int interfaces = 0;
  for (const ModelEntity& f : m.model().entities[2]) {
    EXPECT_EQ(f.source_tag, std::optional<std::int32_t>(1)) << "face " << f.tag;
    interfaces += m.model().face_kind(f.tag) == FaceKind::Interface;
  }
  EXPECT_EQ(interfaces, 1);
  // The four edges around the interface square bound three faces each.
  int three_face_edges = 0;
  for (const ModelEntity& e : m.model().entities[1]) three_face_edges += e.bounds.size() == 3;
  EXPECT_EQ(three_face_edges, 4);
  EXPECT_TRUE(m.classification_warnings().empty());
  EXPECT_THAT(volume_mismatches(m), ::testing::IsEmpty());
}

// --feature-angle 180 disables the geometric split: the marker is one model
// face per region pair and the dual misses the boxes' sharp edges (its
// volume is short), which is what the split repairs.
TEST(ClassifyMarkers, FeatureAngle180KeepsMarkersWhole) {
  const TetSoup soup = read_tetgen_files(kData + "two_boxes.1.node");
  const ClassifiedTetMesh m = classify(soup, angle(180));
  EXPECT_EQ(m.model().count(2), 3u);  // bottom box outside, top box outside, interface
  EXPECT_EQ(volume_mismatches(m), (std::set<std::int32_t>{1, 2}));
}

// A Fichera corner with one marker (an STL's one patch): 14 corners (one
// re-entrant), 21 edges (3 re-entrant), 9 faces.
TEST(ClassifyMarkers, TetgenFicheraOneMarker) {
  const ClassifiedTetMesh m = classify(read_tetgen_files(kData + "fichera.1.ele"));
  EXPECT_EQ(counts(m), (Counts{14, 21, 9, 1}));
  for (const ModelEntity& v : m.model().entities[0]) EXPECT_EQ(v.bounds.size(), 3u) << "vertex " << v.tag;
  for (const ModelEntity& e : m.model().entities[1]) EXPECT_EQ(e.bounds.size(), 2u) << "edge " << e.tag;
  EXPECT_THAT(volume_mismatches(m), ::testing::IsEmpty());
}

// A Medit file whose one triangle ref covers the cube's six sides.
TEST(ClassifyMarkers, MeditCubeOneRef) {
  const TetSoup soup = read_medit_file(kData + "cube_one_ref.mesh");
  ASSERT_TRUE(soup.edges.empty() && soup.corners.empty());
  std::set<std::int32_t> refs;
  for (const TaggedTriangle& t : soup.triangles) refs.insert(t.tag);
  ASSERT_EQ(refs, std::set<std::int32_t>{1});
  const ClassifiedTetMesh m = classify(soup);
  EXPECT_EQ(counts(m), (Counts{8, 12, 6, 1}));
  EXPECT_THAT(volume_mismatches(m), ::testing::IsEmpty());
  // The marker keeps its tag on the first of its faces; the others get fresh
  // tags above it, in mesh order (deterministic).
  std::vector<std::int32_t> tags;
  for (const ModelEntity& f : m.model().entities[2]) tags.push_back(f.tag);
  EXPECT_EQ(tags, (std::vector<std::int32_t>{1, 2, 3, 4, 5, 6}));
  const ClassifiedTetMesh again = classify(soup);
  for (std::size_t f = 0; f < m.num_triangles(); ++f)
    ASSERT_EQ(m.triangle_class(TriId(f)), again.triangle_class(TriId(f)));
  const ClassifiedTetMesh whole = classify(soup, angle(180));
  EXPECT_EQ(counts(whole), (Counts{0, 0, 1, 1}));
  EXPECT_EQ(volume_mismatches(whole), std::set<std::int32_t>{0});
}

// The marker is the faces' group: its tag and its name on every model face it
// gave, also when it spans disconnected parts (two opposite box sides).
TEST(ClassifyMarkers, MarkerIsTheGroupOfItsFaces) {
  TetSoup s = kuhn_lattice(3, 2, 2);
  const ClassifiedTetMesh first = classify(s);
  for (std::size_t f = 0; f < first.num_triangles(); ++f) {
    if (first.triangle_tet(TriId(f), 1).valid()) continue;
    const auto& v = first.triangle(TriId(f));
    TaggedTriangle t;
    bool x_side = true;  // on x = 0 or x = 3: all three vertices there
    for (int i = 0; i < 3; ++i) {
      t.v[i] = first.input_vertex(v[i]);
      x_side = x_side && first.point(v[i]).x == first.point(v[0]).x;
    }
    x_side = x_side && (first.point(v[0]).x == 0 || first.point(v[0]).x == 3);
    t.tag = x_side ? 7 : 8;  // the two x sides: marker 7; the four others: marker 8
    s.triangles.push_back(t);
  }
  s.groups = {NamedGroup{2, 70, "ends", {7}}, NamedGroup{2, 80, "", {8}}, NamedGroup{2, 81, "walls", {8}},
              NamedGroup{3, 1, "steel", {1}}};
  for (double deg : {30.0, 180.0}) {
    const ClassifiedTetMesh m = classify(s, angle(deg));
    std::map<std::int32_t, int> faces_of_marker;
    for (const ModelEntity& f : m.model().entities[2]) {
      ASSERT_TRUE(f.source_tag.has_value()) << "face " << f.tag;
      ++faces_of_marker[*f.source_tag];
      EXPECT_EQ(f.name, *f.source_tag == 7 ? "ends" : "walls") << "face " << f.tag;  // first named group
    }
    EXPECT_EQ(faces_of_marker[7], 2) << deg;                   // disconnected: two faces in either case
    EXPECT_EQ(faces_of_marker[8], deg == 180.0 ? 1 : 4) << deg;  // a ring of four sides: split at 30
    EXPECT_EQ(m.model().entities[3].at(0).name, "steel");
    EXPECT_EQ(m.model().entities[3].at(0).source_tag, std::optional<std::int32_t>(1));
  }
}

// Inferred entities have no source tag; given ones keep theirs.
TEST(ClassifyMarkers, InferredEntitiesHaveNoSourceTag) {
  const ClassifiedTetMesh m = classify(kuhn_lattice(2, 2, 2));
  for (int d = 0; d < 3; ++d)
    for (const ModelEntity& e : m.model().entities[d]) {
      EXPECT_FALSE(e.source_tag.has_value()) << "dim " << d << " tag " << e.tag;
      EXPECT_EQ(e.name, "");
    }
}

// Gmsh 2.2 with physical groups only (tests/data/geo/twovol.geo): the marker
// "ends" over the two end faces x = 0 and x = 2 (disconnected) gives two model
// faces of that name; "interface" one; the sides, which no physical group
// holds, are inferred (no source tag, no name); the volumes keep their names.
TEST(ClassifyMarkers, Gmsh22PhysicalNamesNameTheFaces) {
  const TetSoup soup = read_msh_file(std::string(POLYDUAL_TEST_DATA) + "/gmsh/twovol_v2_physical_bin.msh");
  ASSERT_FALSE(soup.full_classification);
  const ClassifiedTetMesh m = classify(soup);
  EXPECT_EQ(counts(m), (Counts{12, 20, 11, 2}));
  std::map<std::string, int> faces_named;
  for (const ModelEntity& f : m.model().entities[2]) {
    ++faces_named[f.name];
    EXPECT_EQ(f.source_tag.has_value(), !f.name.empty()) << "face " << f.tag;
    if (f.name == "ends") EXPECT_EQ(f.source_tag, std::optional<std::int32_t>(4));
    if (f.name == "interface") EXPECT_EQ(f.source_tag, std::optional<std::int32_t>(3));
  }
  EXPECT_EQ(faces_named, (std::map<std::string, int>{{"", 8}, {"ends", 2}, {"interface", 1}}));
  ASSERT_EQ(m.model().count(3), 2u);
  EXPECT_EQ(m.model().entities[3][0].name, "left");
  EXPECT_EQ(m.model().entities[3][1].name, "right");
  EXPECT_THAT(volume_mismatches(m), ::testing::IsEmpty());
}
