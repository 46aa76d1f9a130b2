// validate() (lib/mesh/validate.h, design §10) on good meshes and on meshes
// broken in one way each: one test per kind of error it reports, so that a
// validate that always said "ok" fails. Meshes are built by hand (boxes of six
// quads) and by the real pipeline (classify + build_dual on generated meshes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "classify/classify.h"
#include "dual/build_dual.h"
#include "generate/domains.h"
#include "generate/random_mesh.h"
#include "mesh/validate.h"

using namespace polydual;

namespace {

// A PolyMesh described as plain lists, so that a test can break one thing
// before building it.
struct FaceSpec {
  std::vector<std::uint32_t> loop;
  std::uint32_t owner, neighbour;  // neighbour CellId::kInvalid on the boundary
  FaceKind kind;
};
struct HandMesh {
  std::vector<Point3> points;
  std::vector<FaceSpec> faces;
  std::vector<std::vector<HalfFace>> cells;

  PolyMesh build() const {
    PolyMesh pm;
    for (const Point3& p : points) pm.add_point(p, ModelRef{3, 1});
    for (const FaceSpec& f : faces) {
      std::vector<PointId> loop;
      for (std::uint32_t p : f.loop) loop.push_back(PointId(p));
      pm.add_face(loop, CellId(f.owner), CellId(f.neighbour), f.kind, f.kind == FaceKind::Interior ? 0 : 1);
    }
    for (std::size_t c = 0; c < cells.size(); ++c) pm.add_cell(cells[c], 1, VertexId(std::uint32_t(c)));
    return pm;
  }
};

// n unit boxes in a row along x ([b, b+1] x [0,1] x [0,1]); box b shares its
// x = b+1 face with box b+1 (owned by b, whose outward normal is +x there).
// Every face's right-hand normal points out of its owner.
HandMesh box_row(int n) {
  HandMesh h;
  auto idx = [n](int i, int j, int k) { return std::uint32_t(i + (n + 1) * (j + 2 * k)); };
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i <= n; ++i) h.points.push_back({double(i), double(j), double(k)});
  h.cells.resize(std::size_t(n));
  const std::uint32_t none = CellId::kInvalid;
  for (int i = 0; i <= n; ++i) {  // the x-faces, +x orientation
    std::vector<std::uint32_t> loop{idx(i, 0, 0), idx(i, 1, 0), idx(i, 1, 1), idx(i, 0, 1)};
    const FaceId f(std::uint32_t(h.faces.size()));
    if (i == 0) {
      std::reverse(loop.begin(), loop.end());
      h.faces.push_back({loop, 0, none, FaceKind::External});
      h.cells[0].push_back(HalfFace(f, 0));
    } else if (i == n) {
      h.faces.push_back({loop, std::uint32_t(n - 1), none, FaceKind::External});
      h.cells[std::size_t(n - 1)].push_back(HalfFace(f, 0));
    } else {
      h.faces.push_back({loop, std::uint32_t(i - 1), std::uint32_t(i), FaceKind::Interior});
      h.cells[std::size_t(i - 1)].push_back(HalfFace(f, 0));
      h.cells[std::size_t(i)].push_back(HalfFace(f, 1));
    }
  }
  for (int b = 0; b < n; ++b) {
    const std::vector<std::vector<std::uint32_t>> loops{
        {idx(b, 0, 0), idx(b + 1, 0, 0), idx(b + 1, 0, 1), idx(b, 0, 1)},   // y = 0, -y
        {idx(b, 1, 0), idx(b, 1, 1), idx(b + 1, 1, 1), idx(b + 1, 1, 0)},   // y = 1, +y
        {idx(b, 0, 0), idx(b, 1, 0), idx(b + 1, 1, 0), idx(b + 1, 0, 0)},   // z = 0, -z
        {idx(b, 0, 1), idx(b + 1, 0, 1), idx(b + 1, 1, 1), idx(b, 1, 1)}};  // z = 1, +z
    for (const auto& loop : loops) {
      h.cells[std::size_t(b)].push_back(HalfFace(FaceId(std::uint32_t(h.faces.size())), 0));
      h.faces.push_back({loop, std::uint32_t(b), none, FaceKind::External});
    }
  }
  return h;
}

// Drops face f from the description (and from its cells), renumbering the rest.
void drop_face(HandMesh& h, std::uint32_t f) {
  h.faces.erase(h.faces.begin() + f);
  for (auto& cell : h.cells) {
    std::vector<HalfFace> kept;
    for (HalfFace x : cell)
      if (x.face().idx != f) kept.push_back(x.face().idx < f ? x : HalfFace(FaceId(x.face().idx - 1), x.side()));
    cell = kept;
  }
}

void expect_sound(const ValidationReport& r, std::size_t cells) {
  EXPECT_EQ(r.cells, cells);
  EXPECT_EQ(r.closed_cells, cells);
  EXPECT_EQ(r.manifold_cells, cells);
  EXPECT_EQ(r.misoriented_cells, 0u);
  EXPECT_EQ(r.slit_cells, 0u);
  EXPECT_EQ(r.face_errors, 0u);
  EXPECT_EQ(r.negative_volume_cells, 0u);
  EXPECT_TRUE(r.open_cells.empty());
}

// The dual of a generated mesh, with its primal.
struct Pipeline {
  ClassifiedTetMesh primal;
  PolyMesh dual;
};
Pipeline pipeline(const TetSoup& soup) {
  Pipeline p{classify(soup), {}};
  p.dual = build_dual(p.primal);
  return p;
}
const Pipeline& cube_domain() {
  static const Pipeline p = pipeline(generate_domain(Domain::Cube, 1500));
  return p;
}
const Pipeline& twomat_domain() {
  static const Pipeline p = pipeline(generate_domain(Domain::TwoMat, 1500));
  return p;
}

std::vector<std::string> only(const std::string& s) { return {s}; }

}  // namespace

// ---- good meshes

TEST(Validate, UnitCubeCellIsSound) {
  const ValidationReport r = validate(box_row(1).build());
  expect_sound(r, 1);
  EXPECT_EQ(r.faces, 6u);
  EXPECT_EQ(r.points, 8u);
  EXPECT_TRUE(r.ok());
  EXPECT_TRUE(r.geometry_ok());
  ASSERT_EQ(r.material_volume.size(), 1u);
  EXPECT_DOUBLE_EQ(r.material_volume.at(1), 1.0);
  EXPECT_DOUBLE_EQ(cell_volume(box_row(1).build(), CellId(0)), 1.0);
}

TEST(Validate, TwoCellsSharingAFaceAreSound) {
  const PolyMesh pm = box_row(2).build();
  const ValidationReport r = validate(pm);
  expect_sound(r, 2);
  EXPECT_EQ(r.faces, 11u);
  EXPECT_EQ(r.points, 12u);
  EXPECT_TRUE(r.ok());
  EXPECT_DOUBLE_EQ(r.material_volume.at(1), 2.0);
  EXPECT_DOUBLE_EQ(cell_volume(pm, CellId(1)), 1.0);
}

TEST(Validate, DualOfRandomMeshIsSoundAndKeepsItsVolume) {
  RandomMeshParams params;
  params.seed = 5;
  params.num_points = 150;
  const Pipeline p = pipeline(random_classified_mesh(params));
  const ValidationReport r = validate(p.dual, &p.primal);
  expect_sound(r, p.primal.num_vertices());  // one region, no fracture: one cell per vertex
  EXPECT_EQ(r.faces, p.dual.num_faces());
  EXPECT_EQ(r.points, p.dual.num_points());
  EXPECT_TRUE(r.ok());
  EXPECT_TRUE(r.missing_model_entities.empty());
  EXPECT_EQ(r.volume_checked_materials, std::vector<std::int32_t>{1});
  EXPECT_TRUE(r.geometry_ok());
  EXPECT_NEAR(r.material_volume.at(1), 1.0, 1e-12);  // the unit box
  EXPECT_NEAR(r.primal_material_volume.at(1), 1.0, 1e-12);
}

TEST(Validate, DualOfDomainsIsSound) {
  for (const Pipeline* p : {&cube_domain(), &twomat_domain()}) {
    // Without fractures a vertex has one side (one cell) per region around it.
    std::size_t sides = 0;
    for (std::size_t v = 0; v < p->primal.num_vertices(); ++v) {
      std::set<std::int32_t> regions;
      for (TetId t : p->primal.vertex_tets(VertexId(std::uint32_t(v)))) regions.insert(p->primal.region(t));
      sides += regions.size();
    }
    const ValidationReport r = validate(p->dual, &p->primal);
    expect_sound(r, sides);
    EXPECT_TRUE(r.ok());
    EXPECT_TRUE(r.missing_model_entities.empty());
    EXPECT_TRUE(r.geometry_ok());
  }
  const ValidationReport r = validate(twomat_domain().dual, &twomat_domain().primal);
  EXPECT_EQ(r.volume_checked_materials, (std::vector<std::int32_t>{1, 2}));
  EXPECT_NEAR(r.material_volume.at(1), 1.0, 1e-12);  // [0,1]^3 and [1,2]x[0,1]^2
  EXPECT_NEAR(r.material_volume.at(2), 1.0, 1e-12);
}

// ---- topology: cells

TEST(Validate, CellWithAFaceRemovedIsOpen) {
  HandMesh h = box_row(1);
  drop_face(h, 5);
  const ValidationReport r = validate(h.build());
  EXPECT_EQ(r.closed_cells, 0u);
  EXPECT_EQ(r.manifold_cells, 0u);
  EXPECT_EQ(r.open_cells, std::vector<CellId>{CellId(0)});
  EXPECT_EQ(r.misoriented_cells, 0u);  // open, not misoriented
  EXPECT_EQ(r.face_errors, 0u);
  EXPECT_FALSE(r.ok());
}

TEST(Validate, OpenCellFromThePipeline) {
  // The real dual with one face taken out of one cell's list (and, to keep the
  // face records consistent, the face's other side dropped too: a hole).
  PolyMesh pm = cube_domain().dual;
  const std::uint32_t c = 7;
  const HalfFace gone = pm.cell(CellId(c))[0];
  std::vector<HalfFace> faces;
  std::vector<std::uint32_t> offsets{0};
  for (std::size_t k = 0; k < pm.num_cells(); ++k) {
    for (HalfFace h : pm.cell(CellId(std::uint32_t(k))))
      if (h.face() != gone.face()) faces.push_back(h);
    offsets.push_back(std::uint32_t(faces.size()));
  }
  pm.cell_faces = faces;
  pm.cell_offsets = offsets;
  const ValidationReport r = validate(pm, &cube_domain().primal);
  const std::size_t sides = pm.face_neighbour[gone.face().idx].valid() ? 2 : 1;
  EXPECT_EQ(r.closed_cells, r.cells - sides);
  EXPECT_NE(std::find(r.open_cells.begin(), r.open_cells.end(), CellId(c)), r.open_cells.end());
  EXPECT_EQ(r.misoriented_cells, 0u);
  EXPECT_EQ(r.face_errors, 1u);  // the face is now listed by no cell
  EXPECT_FALSE(r.ok());
}

TEST(Validate, ReversedFaceIsMisoriented) {
  HandMesh h = box_row(1);
  std::reverse(h.faces[3].loop.begin(), h.faces[3].loop.end());
  const ValidationReport r = validate(h.build());
  EXPECT_EQ(r.closed_cells, 0u);  // each edge of the face is now used twice the same way
  EXPECT_EQ(r.misoriented_cells, 1u);
  EXPECT_EQ(r.open_cells, std::vector<CellId>{CellId(0)});
  EXPECT_EQ(r.face_errors, 0u);  // every face on its own is fine
  EXPECT_FALSE(r.ok());
}

TEST(Validate, ReversedFaceInThePipelineDual) {
  PolyMesh pm = cube_domain().dual;
  // An external face: its only cell is the one made wrong.
  std::size_t f = 0;
  while (pm.face_kind[f] != FaceKind::External) ++f;
  std::reverse(pm.face_points.begin() + pm.face_offsets[f], pm.face_points.begin() + pm.face_offsets[f + 1]);
  const ValidationReport r = validate(pm, &cube_domain().primal);
  EXPECT_EQ(r.closed_cells, r.cells - 1);
  EXPECT_EQ(r.misoriented_cells, 1u);
  EXPECT_EQ(r.open_cells, std::vector<CellId>{pm.face_owner[f]});
  EXPECT_FALSE(r.ok());
}

// ---- topology: faces

// One prism cell over a regular n-gon (unit circumradius, height 1): 2n
// points, so n > 32 takes validate's path for cells of more than 64 points
// (sorted edge keys) and n <= 32 its small-cell path (counts by local index).
HandMesh ngon_prism(int n) {
  HandMesh h;
  const double pi = std::acos(-1.0);
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < n; ++i)
      h.points.push_back({std::cos(2 * pi * i / n), std::sin(2 * pi * i / n), double(z)});
  const std::uint32_t none = CellId::kInvalid, N = std::uint32_t(n);
  FaceSpec bottom{{}, 0, none, FaceKind::External}, top{{}, 0, none, FaceKind::External};
  for (std::uint32_t i = 0; i < N; ++i) {
    bottom.loop.push_back(N - 1 - i);  // normal -z
    top.loop.push_back(N + i);         // normal +z
    h.faces.push_back({{i, (i + 1) % N, N + (i + 1) % N, N + i}, 0, none, FaceKind::External});
  }
  h.faces.push_back(bottom);
  h.faces.push_back(top);
  h.cells.resize(1);
  for (std::size_t f = 0; f < h.faces.size(); ++f) h.cells[0].push_back(HalfFace(FaceId(f), 0));
  return h;
}

TEST(Validate, SmallAndLargeCellsAreClosedOpenOrMisorientedAlike) {
  const double pi = std::acos(-1.0);
  for (int n : {5, 31, 32, 33, 40}) {
    SCOPED_TRACE(n);
    const ValidationReport good = validate(ngon_prism(n).build());
    expect_sound(good, 1);
    EXPECT_NEAR(good.material_volume.at(1), 0.5 * n * std::sin(2 * pi / n), 1e-12);
    HandMesh reversed = ngon_prism(n);
    std::reverse(reversed.faces[2].loop.begin(), reversed.faces[2].loop.end());
    const ValidationReport rev = validate(reversed.build());
    EXPECT_EQ(rev.closed_cells, 0u);
    EXPECT_EQ(rev.misoriented_cells, 1u);
    HandMesh open = ngon_prism(n);
    open.cells[0].pop_back();  // the top cap no longer listed
    const ValidationReport op = validate(open.build());
    EXPECT_EQ(op.closed_cells, 0u);
    EXPECT_EQ(op.misoriented_cells, 0u);
    HandMesh twice = ngon_prism(n);
    twice.cells[0].push_back(HalfFace(FaceId(0), 0));  // a side listed twice: slit, edges used 3 times
    const ValidationReport tw = validate(twice.build());
    EXPECT_EQ(tw.slit_cells, 1u);
    EXPECT_EQ(tw.closed_cells, 0u);
    EXPECT_EQ(tw.manifold_cells, 0u);
  }
}

TEST(Validate, FaceWithFewerThanThreePoints) {
  HandMesh h = box_row(1);
  h.faces[2].loop.resize(2);
  const ValidationReport r = validate(h.build());
  EXPECT_EQ(r.face_errors, 1u);
  EXPECT_FALSE(r.ok());
}

TEST(Validate, FaceWithARepeatedPoint) {
  HandMesh h = box_row(1);
  h.faces[2].loop.push_back(h.faces[2].loop[1]);
  const ValidationReport r = validate(h.build());
  EXPECT_EQ(r.face_errors, 1u);
  EXPECT_FALSE(r.ok());
}

TEST(Validate, FaceWithAPointOutOfRange) {
  HandMesh h = box_row(1);
  h.faces[2].loop[0] = 8;
  const ValidationReport r = validate(h.build());  // must not read past the points
  EXPECT_EQ(r.face_errors, 1u);
  EXPECT_FALSE(r.ok());
}

TEST(Validate, BadOwnerAndNeighbour) {
  {  // owner out of range
    HandMesh h = box_row(2);
    h.faces[4].owner = 2;
    EXPECT_GE(validate(h.build()).face_errors, 1u);
    EXPECT_FALSE(validate(h.build()).ok());
  }
  {  // an interior face without neighbour (kind says External iff no neighbour)
    HandMesh h = box_row(2);
    h.faces[1].neighbour = CellId::kInvalid;
    const ValidationReport r = validate(h.build());
    EXPECT_GE(r.face_errors, 1u);
    EXPECT_FALSE(r.ok());
  }
  {  // an external face given a neighbour
    HandMesh h = box_row(2);
    h.faces[0].neighbour = 1;
    const ValidationReport r = validate(h.build());
    EXPECT_GE(r.face_errors, 1u);
    EXPECT_FALSE(r.ok());
  }
  {  // kinds that disagree with the neighbours: External iff no neighbour
    HandMesh h = box_row(2);
    h.faces[1].kind = FaceKind::External;  // the shared face
    EXPECT_EQ(validate(h.build()).face_errors, 1u);
    h = box_row(2);
    h.faces[0].kind = FaceKind::Interface;  // an outer face
    EXPECT_EQ(validate(h.build()).face_errors, 1u);
  }
  {  // a face whose owner does not list it (listed by the wrong cell)
    HandMesh h = box_row(2);
    h.faces[4].owner = 1;  // a y-face of box 0, listed by box 0
    const ValidationReport r = validate(h.build());
    EXPECT_EQ(r.face_errors, 2u);  // the wrong listing, and the half-face its owner lacks
    EXPECT_EQ(r.closed_cells, 2u);  // the loops themselves still close
    EXPECT_FALSE(r.ok());
  }
  {  // a half-face listed twice by its cell
    HandMesh h = box_row(2);
    h.cells[0].push_back(h.cells[0].back());
    EXPECT_EQ(validate(h.build()).face_errors, 1u);
  }
  {  // the interior face's neighbour side listed by nobody
    HandMesh h = box_row(2);
    h.cells[1].erase(std::find(h.cells[1].begin(), h.cells[1].end(), HalfFace(FaceId(1), 1)));
    const ValidationReport r = validate(h.build());
    EXPECT_EQ(r.face_errors, 1u);
    EXPECT_EQ(r.closed_cells, 1u);
  }
  {  // a half-face naming no face
    HandMesh h = box_row(1);
    h.cells[0].push_back(HalfFace(FaceId(6), 0));
    const ValidationReport r = validate(h.build());
    EXPECT_EQ(r.face_errors, 1u);
    EXPECT_FALSE(r.ok());
  }
}

TEST(Validate, BadFaceInThePipelineDual) {
  PolyMesh pm = cube_domain().dual;
  const std::size_t f = pm.num_faces() / 2;
  pm.face_points[pm.face_offsets[f] + 1] = pm.face_points[pm.face_offsets[f]];  // a repeated point
  const ValidationReport r = validate(pm, &cube_domain().primal);
  EXPECT_GE(r.face_errors, 1u);
  EXPECT_FALSE(r.ok());
}

// ---- model entities (design §10)

TEST(Validate, ModelVertexNotAmongTheDualPoints) {
  const Pipeline& p = cube_domain();
  std::size_t q = 0;
  while (p.dual.point_class[q].dim != 0) ++q;
  const std::int32_t tag = p.dual.point_class[q].tag;
  const std::string name = "model vertex " + std::to_string(tag);
  {  // classified elsewhere
    PolyMesh pm = p.dual;
    pm.point_class[q] = ModelRef{3, 1};
    const ValidationReport r = validate(pm, &p.primal);
    EXPECT_EQ(r.missing_model_entities, only(name));
    EXPECT_FALSE(r.ok());
  }
  {  // classified on it but not at its place
    PolyMesh pm = p.dual;
    pm.points[q] += Vec3{0, 0, 1e-9};
    const ValidationReport r = validate(pm, &p.primal);
    EXPECT_EQ(r.missing_model_entities, only(name));
  }
}

TEST(Validate, ModelEdgeNotCovered) {
  // Every dual point on one model edge reclassified to a model face that the
  // edge bounds: no dual edge lies along the model edge any more.
  const Pipeline& p = cube_domain();
  const ModelEntity& edge = p.primal.model().entities[1].front();
  PolyMesh pm = p.dual;
  int moved = 0;
  for (ModelRef& c : pm.point_class)
    if (c == ModelRef{1, edge.tag}) c = ModelRef{2, edge.bounds.front()}, ++moved;
  EXPECT_GT(moved, 0);
  const ValidationReport r = validate(pm, &p.primal);
  EXPECT_EQ(r.missing_model_entities, only("model edge " + std::to_string(edge.tag)));
  EXPECT_FALSE(r.ok());
}

TEST(Validate, ModelEdgeWithAPointOnItButNoDualEdgeAlongIt) {
  // Covered means dual edges along the edge, not just a point classified on
  // it: keep one point of the edge, away from its model vertices, and move
  // the others to a model face.
  const Pipeline& p = cube_domain();
  const ModelEntity& edge = p.primal.model().entities[1].front();
  PolyMesh pm = p.dual;
  std::vector<std::uint32_t> on_edge;
  for (std::uint32_t q = 0; q < pm.num_points(); ++q)
    if (pm.point_class[q] == ModelRef{1, edge.tag}) on_edge.push_back(q);
  auto next_to_model_vertex = [&](std::uint32_t q) {
    for (std::size_t f = 0; f < pm.num_faces(); ++f) {
      const auto loop = pm.face(FaceId(f));
      for (std::size_t k = 0; k < loop.size(); ++k)
        if (loop[k].idx == q && (pm.point_class[loop[(k + 1) % loop.size()].idx].dim == 0 ||
                                 pm.point_class[loop[(k + loop.size() - 1) % loop.size()].idx].dim == 0))
          return true;
    }
    return false;
  };
  const auto keep = std::find_if_not(on_edge.begin(), on_edge.end(), next_to_model_vertex);
  ASSERT_NE(keep, on_edge.end());
  for (std::uint32_t q : on_edge)
    if (q != *keep) pm.point_class[q] = ModelRef{2, edge.bounds.front()};
  const ValidationReport r = validate(pm, &p.primal);
  EXPECT_EQ(r.missing_model_entities, only("model edge " + std::to_string(edge.tag)));
}

TEST(Validate, ModelFaceWithoutFacesOfItsTag) {
  const Pipeline& p = cube_domain();
  const std::int32_t tag = p.primal.model().entities[2].front().tag, other = p.primal.model().entities[2].back().tag;
  PolyMesh pm = p.dual;
  for (std::int32_t& t : pm.face_tag)
    if (t == tag) t = other;
  const ValidationReport r = validate(pm, &p.primal);
  EXPECT_EQ(r.missing_model_entities, only("model face " + std::to_string(tag)));
  EXPECT_FALSE(r.ok());
}

// ---- geometry: per-material volume against the primal

TEST(Validate, InterfacePointMovedIsAVolumeMismatch) {
  // Two materials meet at the plane x = 1. Moving one dual point of the
  // interface by 1e-3 along x moves volume from one material to the other:
  // both mismatch, the total is kept, and the topology stays ok.
  const Pipeline& p = twomat_domain();
  PolyMesh pm = p.dual;
  std::size_t q = 0;
  const ModelEntity* iface = nullptr;
  for (; q < pm.num_points(); ++q) {
    const ModelRef c = pm.point_class[q];
    if (c.dim != 2) continue;
    iface = p.primal.model().find(2, c.tag);
    if (iface->regions.size() == 2 && iface->regions[0] != iface->regions[1]) break;
  }
  ASSERT_LT(q, pm.num_points());
  pm.points[q].x += 1e-3;
  const ValidationReport r = validate(pm, &p.primal);
  EXPECT_TRUE(r.ok());  // topology only
  EXPECT_FALSE(r.geometry_ok());
  ASSERT_EQ(r.volume_mismatches.size(), 2u);
  EXPECT_EQ(r.volume_mismatches[0].material, 1);
  EXPECT_EQ(r.volume_mismatches[1].material, 2);
  const double shift = r.volume_mismatches[0].dual - r.volume_mismatches[0].primal;
  EXPECT_GT(std::fabs(shift), 1e-9);
  EXPECT_NEAR(r.volume_mismatches[1].dual - r.volume_mismatches[1].primal, -shift, 1e-12);
  for (const VolumeMismatch& m : r.volume_mismatches) {
    EXPECT_EQ(m.primal, r.primal_material_volume.at(m.material));
    EXPECT_EQ(m.dual, r.material_volume.at(m.material));
    EXPECT_DOUBLE_EQ(m.rel_diff, std::fabs(m.dual - m.primal) / std::max(m.dual, m.primal));
    EXPECT_GT(m.rel_diff, r.volume_rel_tol);
  }
  // A looser tolerance accepts the same mesh.
  EXPECT_TRUE(validate(pm, &p.primal, 1e-2).geometry_ok());
}

TEST(Validate, ExternalPointMovedOutwardIsAVolumeMismatch) {
  const Pipeline& p = cube_domain();
  PolyMesh pm = p.dual;
  std::size_t q = 0;
  while (!(pm.point_class[q].dim == 2 && pm.points[q].x == 0)) ++q;  // on the face x = 0
  pm.points[q].x = -1e-4;
  const ValidationReport r = validate(pm, &p.primal);
  ASSERT_EQ(r.volume_mismatches.size(), 1u);
  EXPECT_GT(r.volume_mismatches[0].dual, r.volume_mismatches[0].primal);
}

TEST(Validate, CellOfAnUnknownMaterialIsAVolumeMismatch) {
  const Pipeline& p = cube_domain();
  PolyMesh pm = p.dual;
  pm.cell_material[3] = 99;
  const ValidationReport r = validate(pm, &p.primal);
  ASSERT_EQ(r.volume_mismatches.size(), 2u);
  EXPECT_EQ(r.volume_mismatches[1].material, 99);
  EXPECT_EQ(r.volume_mismatches[1].primal, 0.0);
  EXPECT_EQ(r.volume_mismatches[1].rel_diff, 1.0);
  EXPECT_EQ(r.to_json().find("geometry_ok")->dump(), "false");
}

TEST(Validate, MaterialsBoundedByCurvedFacesAreNotCompared) {
  // Two regions split by centroid: the interface is a jagged surface of
  // triangles in many planes, so neither material is compared.
  RandomMeshParams params;
  params.seed = 3;
  params.num_points = 80;
  params.regions = 2;
  const Pipeline p = pipeline(random_classified_mesh(params));
  const ValidationReport r = validate(p.dual, &p.primal);
  EXPECT_TRUE(r.volume_checked_materials.empty());
  EXPECT_TRUE(r.geometry_ok());
  EXPECT_EQ(r.primal_material_volume.size(), 2u);
}

// ---- defects: the failed checks, each naming its cells (faces, entities, materials)

TEST(Validate, SoundMeshesHaveNoDefects) {
  EXPECT_TRUE(validate(box_row(3).build()).defects().empty());
  EXPECT_TRUE(validate(cube_domain().dual, &cube_domain().primal).defects().empty());
}

TEST(Validate, DefectsNameTheOpenAndReversedCells) {
  HandMesh h = box_row(3);
  drop_face(h, 7);  // a side of box 0 (the x-faces come first: 0..3)
  std::reverse(h.faces[12].loop.begin(), h.faces[12].loop.end());  // a side of box 2, now reversed
  const ValidationReport r = validate(h.build());
  const std::vector<Defect> d = r.defects();
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].check, "open_cells");
  EXPECT_EQ(d[0].count, 2u);
  EXPECT_EQ(d[0].items, (std::vector<std::string>{"cell 0", "cell 2 (a face reversed)"}));
  EXPECT_EQ(defect_line(d[0]), "open_cells: 2 " + d[0].meaning + ": cell 0, cell 2 (a face reversed)");
  EXPECT_EQ(defect_line(d[0], 1), "open_cells: 2 " + d[0].meaning + ": cell 0, and 1 more");
  EXPECT_EQ(defects_sentence(d), defect_line(d[0]));
  const std::string json = defects_json(d).dump(0);
  EXPECT_NE(json.find("\"check\":\"open_cells\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"count\":2"), std::string::npos) << json;
}

TEST(Validate, DefectsNameTheBrokenFacesAndTheCellsListingThem) {
  HandMesh h = box_row(2);
  h.faces[2].loop.resize(2);                 // face 2: two points
  h.cells[0].push_back(HalfFace(FaceId(1), 1));  // box 0 lists box 1's side of face 1
  h.cells[1].push_back(HalfFace(FaceId(1), 1));  // box 1 lists its side of face 1 twice
  const ValidationReport r = validate(h.build());
  EXPECT_EQ(r.error_faces, (std::vector<FaceId>{FaceId(1), FaceId(2)}));
  EXPECT_EQ(r.error_cells, std::vector<CellId>{CellId(0)});
  const std::vector<Defect> d = r.defects();
  ASSERT_GE(d.size(), 1u);
  const Defect& faces = d.back();
  EXPECT_EQ(faces.check, "face_errors");
  EXPECT_EQ(faces.count, 3u);
  EXPECT_EQ(faces.items, (std::vector<std::string>{"face 1", "face 2", "cell 0 (lists a face side not its own)"}));
}

TEST(Validate, DefectsNameTheMaterialsAndTheModelEntities) {
  const Pipeline& p = cube_domain();
  PolyMesh pm = p.dual;
  pm.cell_material[3] = 99;
  for (std::size_t f = 0; f < pm.num_faces(); ++f)
    if (pm.face_kind[f] == FaceKind::External && pm.face_tag[f] == p.primal.model().entities[2][0].tag) pm.face_tag[f] = 77;
  const ValidationReport r = validate(pm, &p.primal);
  const std::vector<Defect> d = r.defects();
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].check, "missing_model_entities");
  EXPECT_EQ(d[0].items, only("model face " + std::to_string(p.primal.model().entities[2][0].tag)));
  EXPECT_EQ(d[1].check, "volume_mismatches");
  EXPECT_EQ(d[1].count, 2u);
  ASSERT_EQ(d[1].items.size(), 2u);
  EXPECT_EQ(d[1].items[1].rfind("material 99: dual ", 0), 0u) << d[1].items[1];
}
