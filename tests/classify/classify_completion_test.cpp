// A full classification (Gmsh msh 4.1 with $Entities) that lacks curves or
// points is completed by inference with a warning; what contradicts itself is
// refused, naming the place (design §3; proofs/classification.md L14). The
// incomplete files are generated domains written by lib/io's msh writer with
// some curves or points left out.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include "classify/classify.h"
#include "exact_volume.h"
#include "core/error.h"
#include "dual/build_dual.h"
#include "generate/domains.h"
#include "generate/random_mesh.h"
#include "io/msh_reader.h"
#include "io/msh_writer.h"

using namespace polydual;
using ::testing::HasSubstr;

namespace {

namespace fs = std::filesystem;

// Writes the soup as msh 4.1 and reads it back (what a user's file gives).
TetSoup through_msh(const TetSoup& s, const std::string& name) {
  const fs::path p = fs::temp_directory_path() /
                     ("polydual_classify_completion_" + std::to_string(::getpid()) + "_" + name + ".msh");
  write_msh(s, p.string());
  TetSoup back = read_msh_file(p.string());
  fs::remove(p);
  return back;
}

std::array<std::size_t, 4> counts(const ClassifiedTetMesh& m) {
  return {m.model().count(0), m.model().count(1), m.model().count(2), m.model().count(3)};
}

std::int32_t max_tag(const auto& tagged) {
  std::int32_t mx = std::numeric_limits<std::int32_t>::min();
  for (const auto& t : tagged) mx = std::max(mx, t.tag);
  return mx;
}

bool volumes_match(const ClassifiedTetMesh& m) {
  return polydual::testing::exact_dual_volumes(build_dual(m)) == polydual::testing::exact_primal_volumes(m);
}

const TetSoup& fichera() {
  static const TetSoup s = generate_domain(Domain::Fichera, 3000);
  return s;
}

// The tag of a curve between two of the Fichera's outer faces, and of one
// between two others (the first and the last curve of the generator).
std::int32_t curve_tag(std::size_t which) {
  std::set<std::int32_t> tags;
  for (const TaggedEdge& e : fichera().edges) tags.insert(e.tag);
  return which == 0 ? *tags.begin() : *tags.rbegin();
}

}  // namespace

TEST(ClassifyCompletion, CompleteFileIsTakenAsIs) {
  const TetSoup s = through_msh(fichera(), "complete");
  ASSERT_TRUE(s.full_classification);
  const ClassifiedTetMesh m = classify(s);
  EXPECT_EQ(counts(m), (std::array<std::size_t, 4>{14, 21, 9, 1}));
  EXPECT_THAT(m.classification_warnings(), ::testing::IsEmpty());
  for (int d = 0; d < 4; ++d)
    for (const ModelEntity& e : m.model().entities[d]) EXPECT_EQ(e.source_tag, std::optional<std::int32_t>(e.tag));
}

// A curve left out: the model faces meeting along it get an inferred model
// edge, tagged above the file's largest curve tag, and a warning naming the
// first edge; the dual then covers the domain exactly.
TEST(ClassifyCompletion, MissingCurveIsInferred) {
  TetSoup s = fichera();
  const std::int32_t dropped = curve_tag(0);
  std::set<std::array<double, 3>> dropped_points;
  for (const TaggedEdge& e : s.edges)
    if (e.tag == dropped)
      for (auto v : e.v) dropped_points.insert({s.points[v].x, s.points[v].y, s.points[v].z});
  std::erase_if(s.edges, [&](const TaggedEdge& e) { return e.tag == dropped; });
  const std::int32_t largest = max_tag(s.edges);
  s = through_msh(s, "no_curve");
  ASSERT_TRUE(s.full_classification);
  const ClassifiedTetMesh m = classify(s);
  EXPECT_EQ(counts(m), (std::array<std::size_t, 4>{14, 21, 9, 1}));
  ASSERT_EQ(m.classification_warnings().size(), 1u);
  const std::string& w = m.classification_warnings()[0];
  EXPECT_THAT(w, HasSubstr(s.source + ": incomplete classification completed by inference: 1 model edge added (tags " +
                           std::to_string(largest + 1) + ")"));
  EXPECT_THAT(w, HasSubstr("no curve of the file covers"));
  // The first place it names is an edge of the left-out curve.
  unsigned a = 0, b = 0;
  ASSERT_EQ(std::sscanf(w.c_str() + w.rfind("at edge ("), "at edge (%u, %u)", &a, &b), 2) << w;
  for (unsigned v : {a, b}) {
    const Point3& p = s.points.at(v - 1);
    EXPECT_TRUE(dropped_points.count({p.x, p.y, p.z})) << w;
  }
  const ModelEntity* added = m.model().find(1, largest + 1);
  ASSERT_NE(added, nullptr);
  EXPECT_FALSE(added->source_tag.has_value());
  EXPECT_EQ(added->bounds.size(), 2u);
  for (const ModelEntity& e : m.model().entities[1])
    if (e.tag != largest + 1) EXPECT_EQ(e.source_tag, std::optional<std::int32_t>(e.tag));
  EXPECT_TRUE(volumes_match(m));
}

// Points left out, where curves meet (Fichera) and where a curve ends inside
// the domain (the fracture's free edges): inferred, tagged above the largest
// point tag left, one warning.
TEST(ClassifyCompletion, MissingPointsAreInferred) {
  for (Domain d : {Domain::Fichera, Domain::Fracture}) {
    const TetSoup full = generate_domain(d, 3000);
    const ClassifiedTetMesh reference = classify(through_msh(full, "reference"));
    TetSoup s = full;
    ASSERT_GE(s.corners.size(), 4u);
    s.corners.resize(2);  // keep two
    const std::int32_t largest = max_tag(s.corners);
    s = through_msh(s, "few_points");
    const ClassifiedTetMesh m = classify(s);
    EXPECT_EQ(counts(m), counts(reference)) << domain_name(d);
    const std::size_t added = reference.model().count(0) - 2;
    ASSERT_EQ(m.classification_warnings().size(), 1u) << domain_name(d);
    EXPECT_THAT(m.classification_warnings()[0],
                HasSubstr(std::to_string(added) + " model vertices added (tags " + std::to_string(largest + 1)));
    EXPECT_THAT(m.classification_warnings()[0], HasSubstr("at no point of the file, the first at vertex "));
    for (const ModelEntity& v : m.model().entities[0])
      EXPECT_TRUE(v.source_tag ? v.tag == *v.source_tag && v.tag <= largest : v.tag > largest) << v.tag;
  }
}

// No curve and no point at all: both completed (fresh tags from 1), two
// warnings, the same model as the complete file, the exact volume identity.
TEST(ClassifyCompletion, NoCurvesNoPoints) {
  TetSoup s = fichera();
  s.edges.clear();
  s.corners.clear();
  s = through_msh(s, "surfaces_only");
  ASSERT_TRUE(s.full_classification);
  const ClassifiedTetMesh m = classify(s);
  EXPECT_EQ(counts(m), (std::array<std::size_t, 4>{14, 21, 9, 1}));
  ASSERT_EQ(m.classification_warnings().size(), 2u);
  EXPECT_THAT(m.classification_warnings()[0], HasSubstr("14 model vertices added (tags 1..14)"));
  EXPECT_THAT(m.classification_warnings()[1], HasSubstr("21 model edges added (tags 1..21)"));
  EXPECT_TRUE(volumes_match(m));
}

// One point tag on two vertices, one surface tag on two disconnected faces:
// the file's tag stays on the first, the others get fresh tags and a warning.
TEST(ClassifyCompletion, PiecesOfOneTagAreSeparated) {
  TetSoup s = fichera();
  const std::int32_t points_above = max_tag(s.corners), surfaces_above = max_tag(s.triangles);
  s.corners[1].tag = s.corners[0].tag;
  // Two faces of the Fichera that share no edge: x = 0 and the re-entrant x = 0.5.
  std::int32_t outer = 0, inner = 0;
  for (const TaggedTriangle& t : s.triangles) {
    const bool all0 = s.points[t.v[0]].x == 0 && s.points[t.v[1]].x == 0 && s.points[t.v[2]].x == 0;
    const bool all_half = s.points[t.v[0]].x == 0.5 && s.points[t.v[1]].x == 0.5 && s.points[t.v[2]].x == 0.5;
    if (all0) outer = t.tag;
    if (all_half) inner = t.tag;
  }
  ASSERT_NE(outer, 0);
  ASSERT_NE(inner, 0);
  for (TaggedTriangle& t : s.triangles)
    if (t.tag == inner) t.tag = outer;
  s = through_msh(s, "pieces");
  const ClassifiedTetMesh m = classify(s);
  EXPECT_EQ(m.model().count(0), 14u);
  EXPECT_EQ(m.model().count(2), 9u);
  const auto& w = m.classification_warnings();
  ASSERT_EQ(w.size(), 2u);
  EXPECT_THAT(w[0], HasSubstr("1 model vertex added (tags " + std::to_string(points_above + 1) +
                              ") for pieces of the file's points"));
  EXPECT_THAT(w[1], HasSubstr("1 model face added (tags " + std::to_string(surfaces_above + 1) +
                              ") for pieces of the file's surfaces that are not one model face"));
  EXPECT_THAT(w[1], HasSubstr("surface " + std::to_string(outer) + " at triangle ("));
  const ModelEntity* piece = m.model().find(2, surfaces_above + 1);
  ASSERT_NE(piece, nullptr);
  EXPECT_EQ(piece->source_tag, std::optional<std::int32_t>(outer));
}

// A curve whose edges lie on different surfaces is a contradiction, named at
// the edge and at the curve's first edge.
TEST(ClassifyCompletion, CurveOnDifferentSurfacesIsRefused) {
  TetSoup s = fichera();
  const std::int32_t a = curve_tag(0), b = curve_tag(1);
  ASSERT_NE(a, b);
  for (TaggedEdge& e : s.edges)
    if (e.tag == b) { e.tag = a; break; }  // one edge of curve b claimed by curve a
  s = through_msh(s, "contradiction");
  try {
    classify(s);
    FAIL() << "expected a contradiction";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(s.source));
    EXPECT_THAT(e.what(), HasSubstr("edge ("));
    EXPECT_THAT(e.what(), HasSubstr("contradiction: the file classifies this edge on curve " + std::to_string(a)));
    EXPECT_THAT(e.what(), HasSubstr("but the triangles at this edge lie on surfaces {"));
  }
}

// A triangle given two surfaces, and a boundary triangle given none, stay
// errors in a full classification.
TEST(ClassifyCompletion, TriangleContradictionsAreRefused) {
  TetSoup s = fichera();
  s.full_classification = true;
  TaggedTriangle twice = s.triangles.front();
  twice.tag = s.triangles.back().tag;
  ASSERT_NE(twice.tag, s.triangles.front().tag);
  s.triangles.push_back(twice);
  EXPECT_THROW(
      try { classify(s); } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("triangle classified on two model faces"));
        throw;
      },
      InputError);
  TetSoup t = fichera();
  t.full_classification = true;
  t.triangles.pop_back();
  EXPECT_THROW(
      try { classify(t); } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("contradiction: the triangle lies on the external boundary"));
        throw;
      },
      InputError);
}

// A full classification is not split by the feature angle: one surface tag
// over two sides of a box stays one model face (a marker would be split).
TEST(ClassifyCompletion, FullClassificationKeepsItsFaces) {
  TetSoup s = kuhn_lattice(2, 2, 2);
  const ClassifiedTetMesh first = classify(s);
  for (std::size_t f = 0; f < first.num_triangles(); ++f) {
    if (first.triangle_tet(TriId(f), 1).valid()) continue;
    TaggedTriangle t;
    const auto v = first.triangle(TriId(f));
    for (int i = 0; i < 3; ++i) t.v[i] = first.input_vertex(v[i]);
    auto all = [&](double Vec3::*c, double value) {
      return first.point(v[0]).*c == value && first.point(v[1]).*c == value && first.point(v[2]).*c == value;
    };
    // The sides x = 0 and y = 0 (adjacent) share tag 1; the others have their own.
    t.tag = all(&Vec3::x, 0) || all(&Vec3::y, 0) ? 1 : all(&Vec3::x, 2) ? 3 : all(&Vec3::y, 2) ? 4
                                                           : all(&Vec3::z, 0) ? 5 : 6;
    s.triangles.push_back(t);
  }
  s.full_classification = true;
  const ClassifiedTetMesh full = classify(s);
  EXPECT_EQ(full.model().count(2), 5u);
  EXPECT_FALSE(full.classification_warnings().empty());  // its edges and vertices were inferred
  s.full_classification = false;
  const ClassifiedTetMesh markers = classify(s);
  EXPECT_EQ(markers.model().count(2), 6u);
  EXPECT_TRUE(markers.classification_warnings().empty());
}
