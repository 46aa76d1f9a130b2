// Classification inference and checks (design §3).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <tuple>

#include "classify/classify.h"
#include "core/error.h"
#include "generate/random_mesh.h"

using namespace polydual;
using ::testing::HasSubstr;

namespace {
// All boundary triangles of a soup (from a first classification), tagged 1..6
// by the box side they lie on.
std::vector<TaggedTriangle> box_triangles(const TetSoup& s) {
  ClassifiedTetMesh m = classify(s);
  std::vector<TaggedTriangle> out;
  for (std::size_t f = 0; f < m.num_triangles(); ++f) {
    if (m.triangle_tet(TriId(f), 1).valid()) continue;
    const auto& v = m.triangle(TriId(f));
    TaggedTriangle t;
    for (int i = 0; i < 3; ++i) t.v[i] = m.input_vertex(v[i]);  // the soup's numbering
    t.tag = m.triangle_class(TriId(f)).tag;
    out.push_back(t);
  }
  return out;
}
}  // namespace

TEST(Classify, BoxByInference) {
  ClassifiedTetMesh m = classify(kuhn_lattice(3, 3, 3));
  EXPECT_EQ(m.model().count(0), 8u);
  EXPECT_EQ(m.model().count(1), 12u);
  EXPECT_EQ(m.model().count(2), 6u);
  EXPECT_EQ(m.model().count(3), 1u);
  for (const ModelEntity& e : m.model().entities[1]) EXPECT_EQ(e.bounds.size(), 2u);  // each box edge: 2 faces
  for (const ModelEntity& v : m.model().entities[0]) EXPECT_EQ(v.bounds.size(), 3u);  // each corner: 3 edges
}

TEST(Classify, FeatureAngleControlsSplitting) {
  ClassifyParams p;
  p.feature_angle_deg = 120;  // box edges (90 degrees) are within it: one face
  ClassifiedTetMesh m = classify(kuhn_lattice(2, 2, 2), p);
  EXPECT_EQ(m.model().count(2), 1u);
  EXPECT_EQ(m.model().count(1), 0u);
  EXPECT_EQ(m.model().count(0), 0u);
  p.feature_angle_deg = 0;
  EXPECT_THROW(classify(kuhn_lattice(2, 2, 2), p), UsageError);
}

TEST(Classify, InterfaceBetweenTwoRegions) {
  ClassifiedTetMesh m = classify(kuhn_lattice(4, 2, 2, 1, 1, 1, 2));
  int interfaces = 0;
  for (const ModelEntity& f : m.model().entities[2])
    if (f.regions.size() == 2 && f.regions[0] != f.regions[1]) ++interfaces;
  EXPECT_EQ(interfaces, 1);
  EXPECT_EQ(m.model().count(2), 11u);
}

// The random fracture is a zigzag sheet of tet faces under one tag: the
// feature angle splits it at its bends into pieces that all keep the tag as
// their source; with the angle at 180 it is one face. Either way its free
// boundary (model edges bounding one fracture piece and nothing else) exists.
TEST(Classify, FractureHasFreeBoundaryEdges) {
  RandomMeshParams p;
  p.seed = 11;
  p.num_points = 300;
  p.fracture = true;
  for (double angle : {30.0, 180.0}) {
    ClassifyParams cp;
    cp.feature_angle_deg = angle;
    ClassifiedTetMesh m = classify(random_classified_mesh(p), cp);
    const ModelEntity* fr = m.model().find(2, kRandomFractureTag);
    ASSERT_NE(fr, nullptr);
    ASSERT_EQ(fr->regions.size(), 2u);
    EXPECT_EQ(fr->regions[0], fr->regions[1]);
    std::set<std::int32_t> pieces;
    for (const ModelEntity& f : m.model().entities[2])
      if (f.source_tag == kRandomFractureTag) {
        pieces.insert(f.tag);
        EXPECT_EQ(face_kind(f), FaceKind::Fracture);
      }
    if (angle == 180.0) EXPECT_EQ(pieces.size(), 1u);
    else EXPECT_GT(pieces.size(), 1u);
    int free_edges = 0;  // model edges bounding one fracture piece only
    for (const ModelEntity& e : m.model().entities[1])
      if (e.bounds.size() == 1 && pieces.count(e.bounds[0])) ++free_edges;
    EXPECT_GE(free_edges, 1) << angle;
  }
}

TEST(Classify, GivenTagsAreKeptAndDeterministic) {
  TetSoup s = kuhn_lattice(2, 2, 2);
  s.triangles = box_triangles(s);
  for (auto& t : s.triangles) t.tag += 100;
  ClassifiedTetMesh a = classify(s), b = classify(s);
  ASSERT_EQ(a.model().count(2), 6u);
  for (const ModelEntity& f : a.model().entities[2]) EXPECT_GT(f.tag, 100);
  for (std::size_t f = 0; f < a.num_triangles(); ++f) EXPECT_EQ(a.triangle_class(TriId(f)), b.triangle_class(TriId(f)));
}

// The model depends on the boundary (points, model-face triangles, tags), not
// on the tets that fill the regions: the same soup with its tets in reverse
// order (each rotated by an even permutation, so still positive) gives the
// same model faces with the same tags and the same classified edges. The tet
// order decides which tet is a fracture triangle's first, so it must decide
// neither the sheet's orientation in the feature test nor the order in which
// the pieces of a split marker get their tags.
TEST(Classify, TetOrderDoesNotChangeTheModel) {
  auto faces = [](const ClassifiedTetMesh& m) {
    std::set<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::int32_t>> s;
    for (std::size_t f = 0; f < m.num_triangles(); ++f) {
      if (!m.on_model_face(TriId(f))) continue;
      auto v = m.triangle(TriId(f));
      std::sort(v.begin(), v.end());
      s.insert({v[0].idx, v[1].idx, v[2].idx, m.triangle_class(TriId(f)).tag});
    }
    return s;
  };
  auto edges = [](const ClassifiedTetMesh& m) {
    std::set<std::tuple<std::uint32_t, std::uint32_t, int, std::int32_t>> s;
    for (std::size_t e = 0; e < m.num_edges(); ++e)
      if (const ModelRef r = m.edge_class(EdgeId(e)); r.dim < 3)
        s.insert({m.edge(EdgeId(e))[0].idx, m.edge(EdgeId(e))[1].idx, r.dim, r.tag});
    return s;
  };
  std::size_t split_sheets = 0;  // meshes whose fracture marker became several model faces
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 150 + int(seed % 5) * 50;
    p.network = seed % 2 == 0;
    p.fracture = true;
    const TetSoup soup = random_classified_mesh(p);
    TetSoup reordered = soup;
    std::reverse(reordered.tets.begin(), reordered.tets.end());
    std::reverse(reordered.tet_region.begin(), reordered.tet_region.end());
    for (auto& t : reordered.tets) t = {t[1], t[2], t[0], t[3]};
    const ClassifiedTetMesh a = classify(soup), b = classify(reordered);
    EXPECT_EQ(faces(b), faces(a)) << "seed " << seed;
    EXPECT_EQ(edges(b), edges(a)) << "seed " << seed;
    for (int d = 0; d <= 3; ++d) EXPECT_EQ(b.model().count(d), a.model().count(d)) << "seed " << seed;
    std::size_t pieces = 0;
    for (const ModelEntity& f : a.model().entities[2]) pieces += f.source_tag == kRandomFractureTag;
    split_sheets += pieces > 1;
  }
  EXPECT_GE(split_sheets, 10u);  // not vacuous: the feature test split sheets
}

TEST(Classify, FullClassificationContradictionsAreReported) {
  TetSoup s = kuhn_lattice(2, 2, 2);
  s.triangles = box_triangles(s);
  s.full_classification = true;
  s.triangles.pop_back();  // one boundary triangle classified on no model face
  try {
    classify(s);
    FAIL() << "expected a contradiction";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("contradiction"));
    EXPECT_THAT(e.what(), HasSubstr("external boundary"));
  }
  TetSoup t = kuhn_lattice(2, 2, 2);
  t.triangles = box_triangles(t);
  t.triangles[0].v = {t.tets[0][0], t.tets[0][1], 1000};
  EXPECT_THROW(classify(t), InputError);
}

// One marker INT32_MAX over the six sides: split into six faces, the first
// keeps it and fresh tags cannot go above it, so they are the smallest
// positive ones; at 180 degrees the marker is one face.
TEST(Classify, TagsNearInt32MaxDoNotOverflow) {
  TetSoup s = kuhn_lattice(2, 2, 2);
  s.triangles = box_triangles(s);
  for (auto& t : s.triangles) t.tag = std::numeric_limits<std::int32_t>::max();
  ClassifiedTetMesh m = classify(s);
  std::vector<std::int32_t> tags;
  for (const ModelEntity& f : m.model().entities[2]) {
    tags.push_back(f.tag);
    EXPECT_EQ(f.source_tag, std::numeric_limits<std::int32_t>::max());
  }
  EXPECT_EQ(tags, (std::vector<std::int32_t>{1, 2, 3, 4, 5, std::numeric_limits<std::int32_t>::max()}));
  ClassifyParams p;
  p.feature_angle_deg = 180;
  EXPECT_EQ(classify(s, p).model().count(2), 1u);
}

// validate(): a value outside (0, 180] throws UsageError naming the field, its
// unit and the range; classify() refuses such params before reading the soup.
TEST(Classify, ParamsValidateNamesFieldUnitAndRange) {
  for (double bad : {0.0, -1.0, 180.5, std::nan("")}) {
    ClassifyParams p;
    p.feature_angle_deg = bad;
    try {
      p.validate();
      FAIL() << "feature_angle_deg = " << bad << " accepted";
    } catch (const UsageError& e) {
      EXPECT_THAT(e.what(), HasSubstr("feature_angle_deg"));
      EXPECT_THAT(e.what(), HasSubstr("degrees"));
      EXPECT_THAT(e.what(), HasSubstr("(0, 180]"));
    }
    EXPECT_THROW(classify(kuhn_lattice(1, 1, 1), p), UsageError);
  }
  for (double good : {1e-9, 30.0, ClassifyParams::kMaxFeatureAngleDeg}) {
    ClassifyParams p;
    p.feature_angle_deg = good;
    EXPECT_NO_THROW(p.validate()) << good;
  }
  for (double bad : {0.0, 181.0}) {
    ClassifyParams p;
    p.strong_angle_deg = bad;
    EXPECT_THROW(p.validate(), UsageError) << bad;
  }
  ClassifyParams zero_chain;
  zero_chain.min_feature_chain_edges = 0;
  try {
    zero_chain.validate();
    FAIL() << "min_feature_chain_edges = 0 accepted";
  } catch (const UsageError& e) {
    EXPECT_THAT(e.what(), HasSubstr("min_feature_chain_edges"));
  }
  ClassifyParams p;
  p.feature_angle_deg = 42.5;
  EXPECT_EQ(p.to_json().dump(0),
            "{\"feature_angle_deg\":42.5,\"strong_angle_deg\":60,\"min_feature_chain_edges\":3}");
}

// The rule that names a model face from its regions (one place: lib/mesh).
TEST(Classify, FaceKindFromRegions) {
  ClassifiedTetMesh m = classify(kuhn_lattice(4, 2, 2, 1, 1, 1, 2));
  int external = 0, interface = 0;
  for (const ModelEntity& f : m.model().entities[2]) {
    const FaceKind k = m.model().face_kind(f.tag);
    EXPECT_EQ(k, face_kind(f));
    external += k == FaceKind::External;
    interface += k == FaceKind::Interface;
    EXPECT_EQ(k == FaceKind::External, f.regions.size() == 1);
  }
  EXPECT_EQ(interface, 1);
  EXPECT_EQ(external, 10);
  EXPECT_EQ(face_kind(ModelEntity{2, 5, {1}, {1, 1}}), FaceKind::Fracture);
  EXPECT_THROW(m.model().face_kind(123456), std::out_of_range);
}

// Coordinates the floating-point stages cannot take (fuzz_pipeline: 3.3e81
// overflowed a face normal and reached the optimiser as NaN) are refused by
// name; a mesh merely far from the origin or small is kept.
TEST(Classify, CoordinatesOutOfTheDoubleStagesRangeAreRefused) {
  TetSoup s = kuhn_lattice(1, 1, 1);
  s.source = "big.mesh";
  s.points[3].x = 3.3e81;
  try {
    classify(s);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("big.mesh: vertex 4: coordinate 3.3e+81 exceeds 1e30"));
  }
  TetSoup tiny = kuhn_lattice(1, 1, 1);
  for (auto& p : tiny.points) p = p * 1e-40;
  EXPECT_THROW(classify(tiny), InputError);
  TetSoup ok = kuhn_lattice(1, 1, 1);
  for (auto& p : ok.points) p = p * 1e-6 + Point3{1e6, -1e6, 3e5};
  EXPECT_NO_THROW(classify(ok));
}
