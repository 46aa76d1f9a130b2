// Dual construction (design §4) and its invariants (design §10) on Kuhn lattices
// and random classified tet meshes.
#include <gtest/gtest.h>

#include <CGAL/Gmpq.h>

#include <cmath>
#include <iostream>
#include <map>
#include <set>

#include "classify/classify.h"
#include "core/error.h"
#include "dual/build_dual.h"
#include "dual/central_points.h"
#include "exact_volume.h"
#include "generate/random_mesh.h"
#include "io/unattached.h"
#include "mesh/validate.h"
#include "quality/star_verdict.h"

using namespace polydual;

namespace {



std::size_t count_sides(const ClassifiedTetMesh& m) {
  // Independent count: components of each vertex star through non-model triangles (BFS).
  std::size_t total = 0;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    auto star = m.vertex_tets(VertexId(v));
    std::set<std::uint32_t> left;
    for (TetId t : star) left.insert(t.idx);
    while (!left.empty()) {
      ++total;
      std::vector<std::uint32_t> stack{*left.begin()};
      left.erase(left.begin());
      while (!stack.empty()) {
        TetId t(stack.back());
        stack.pop_back();
        for (int j = 0; j < 4; ++j) {
          if (m.tet(t)[j] == VertexId(v)) continue;  // face opposite v does not contain v
          TetId s = m.tet_neighbor(t, j);
          if (!s.valid() || m.on_model_face(m.tet_triangle(t, j))) continue;
          if (left.erase(s.idx)) stack.push_back(s.idx);
        }
      }
    }
  }
  return total;
}

// What a checked dual contained (for tests over many meshes: did they
// exercise what they are meant to?).
struct DualCounts {
  std::size_t interface_faces = 0, fracture_faces = 0, merged_points = 0;
  std::size_t fracture_tags = 0;  // distinct sheet markers (source tags) of fracture model faces
  std::size_t multi_chain_edges = 0;  // edges whose tets fall into several chains
};

// Meshes checked by check_invariants with a model vertex on no model edge
// (model faces touching at a point: build_dual.cpp touch_vertex).
std::size_t g_touch_meshes = 0;

DualCounts check_invariants(const TetSoup& soup, bool planar, const std::string& what) {
  SCOPED_TRACE(what);
  ClassifiedTetMesh m = classify(soup);
  DualStats st;
  PolyMesh pm = build_dual(m, {}, &st);
  DualCounts counts;
  counts.merged_points = st.merged_points;
  counts.multi_chain_edges = m.multi_chain_edges().size();
  for (FaceKind k : pm.face_kind) {
    counts.interface_faces += k == FaceKind::Interface;
    counts.fracture_faces += k == FaceKind::Fracture;
  }
  std::set<std::int32_t> sheets;
  for (const ModelEntity& f : m.model().entities[2])
    if (face_kind(f) == FaceKind::Fracture && f.source_tag) sheets.insert(*f.source_tag);
  counts.fracture_tags = sheets.size();
  g_touch_meshes += std::any_of(m.model().entities[0].begin(), m.model().entities[0].end(),
                                [](const ModelEntity& v) { return v.bounds.empty(); });
  ValidationReport r = validate(pm, &m);
  EXPECT_EQ(r.face_errors, 0u);
  EXPECT_EQ(r.closed_cells, r.cells);
  // Every model entity is on the dual (L4), also a model vertex where a single
  // model edge ends inside a model face (build_dual.cpp add_cap).
  EXPECT_TRUE(r.missing_model_entities.empty()) << r.missing_model_entities.front();
  EXPECT_EQ(pm.num_cells(), count_sides(m));
  // Interior faces: two distinct cells; external faces: one.
  for (std::size_t f = 0; f < pm.num_faces(); ++f) {
    if (pm.face_kind[f] == FaceKind::External) EXPECT_FALSE(pm.face_neighbour[f].valid());
    else EXPECT_TRUE(pm.face_neighbour[f].valid());
  }
  // Every represented model vertex is a dual point at the same place.
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    if (m.vertex_class(VertexId(v)).dim != 0) continue;
    const std::string name = "model vertex " + std::to_string(m.vertex_class(VertexId(v)).tag);
    bool found = false;
    for (std::size_t p = 0; p < pm.num_points() && !found; ++p)
      found = pm.point_class[p] == m.vertex_class(VertexId(v)) && pm.points[p] == m.point(VertexId(v));
    EXPECT_TRUE(found) << "model vertex at primal vertex " << v;
  }
  if (planar) {
    auto dv = polydual::testing::exact_dual_volumes(pm);
    auto pv = polydual::testing::exact_primal_volumes(m);
    EXPECT_EQ(dv.size(), pv.size());
    for (auto& [tag, q] : pv) EXPECT_TRUE(dv[tag] == q) << "material " << tag << ": dual " << CGAL::to_double(dv[tag]) / 6 << " primal " << CGAL::to_double(q) / 6;
  }
  return counts;
}

// Cells with 8 points and 6 quadrilateral faces (cubes and boxes).
std::size_t count_boxes(const PolyMesh& pm) {
  std::size_t boxes = 0;
  for (std::size_t c = 0; c < pm.num_cells(); ++c) {
    auto faces = pm.cell(CellId(c));
    bool quads = std::all_of(faces.begin(), faces.end(), [&](HalfFace h) { return pm.face(h.face()).size() == 4; });
    boxes += pm.cell_points(CellId(c)).size() == 8 && faces.size() == 6 && quads;
  }
  return boxes;
}

}  // namespace

TEST(Dual, KuhnLatticeGivesCubes) {
  TetSoup s = kuhn_lattice(4, 4, 4);
  ClassifiedTetMesh m = classify(s);
  DualStats st;
  PolyMesh pm = build_dual(m, {}, &st);
  EXPECT_EQ(pm.num_cells(), 125u);  // one per lattice vertex
  // Interior vertices (3^3 = 27) give cubes: 8 points, 6 quadrilateral faces.
  EXPECT_EQ(count_boxes(pm), 125u);  // boundary cells are boxes too (half/quarter/eighth cubes)
  auto verdicts = star_shaped_verdicts(pm);
  for (auto& v : verdicts) EXPECT_TRUE(v.valid);
  EXPECT_GT(st.merged_points, 0u);
}

// A Kuhn lattice whose interior vertices move by ~1e-7 of the spacing: the six
// tets of a cube are then no longer cospherical (no exact merge), but their
// centres lie within 1e-6 of each other. The short-edge collapse (default
// tolerance 1e-3 x mean edge) joins them, and every cell is a cube or box
// again; without it the cells keep their tiny edges.
TEST(Dual, ShortEdgeCollapseRestoresPerturbedLattice) {
  TetSoup s = kuhn_lattice(4, 4, 4);
  std::uint64_t state = 12345;
  auto jitter = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return (double(state >> 11) * 0x1p-53 - 0.5) * 2e-7;
  };
  for (Point3& p : s.points)
    if (p.x > 0 && p.x < 4 && p.y > 0 && p.y < 4 && p.z > 0 && p.z < 4) p += Vec3{jitter(), jitter(), jitter()};
  ClassifiedTetMesh m = classify(s);
  DualParams off;
  off.collapse_tolerance = 0;
  DualStats st_off, st_on;
  PolyMesh raw = build_dual(m, off, &st_off);
  PolyMesh pm = build_dual(m, {}, &st_on);
  EXPECT_EQ(st_off.collapsed_points, 0u);
  EXPECT_GT(st_on.collapsed_points, 0u);
  EXPECT_LT(pm.num_points(), raw.num_points());
  // The interior cells (3^3 = 27 interior lattice vertices) are cubes only
  // after the collapse.
  EXPECT_LT(count_boxes(raw), 125u - 27u + 1u);
  EXPECT_EQ(count_boxes(pm), 125u);
  ValidationReport r = validate(pm, &m);
  EXPECT_EQ(r.face_errors, 0u);
  EXPECT_EQ(r.closed_cells, r.cells);
  check_invariants(s, true, "perturbed kuhn lattice");
}

TEST(Dual, KuhnLatticeTwoMaterials) {
  check_invariants(kuhn_lattice(4, 3, 3, 1, 1, 1, 2), true, "kuhn 2 materials");
}

TEST(Dual, RandomMeshInvariants) {
  // 2600 random classified meshes: one region (planar faces: exact volume
  // identity), two regions (jagged interface), with fracture, with two sheets
  // crossing (one ending inside, one reaching the outer boundary), with
  // construction points, free curves and sheet parts outside the volume, lattice points,
  // three crossing sheets, fins on the wall, a notched (concave) box, three
  // materials touching along edges with the outside on both sides.
  // Each family must exercise what it is there for: interface faces in the
  // two-region meshes, fracture faces (capped on both sides) in the fractured
  // ones, exact merges of cospherical centres in the lattice ones.
  std::size_t meshes[10] = {}, interface_meshes = 0, fracture_meshes = 0, merging_meshes = 0,
              crossing_meshes = 0, unattached_meshes = 0, network_meshes = 0, fin_meshes = 0, notch_meshes = 0,
              touching_meshes = 0;
  for (std::uint64_t seed = 1; seed <= 260; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 20 + int(seed % 30);
    check_invariants(random_classified_mesh(p), true, "single seed " + std::to_string(seed));
    ++meshes[0];
    p.regions = 2;
    interface_meshes += check_invariants(random_classified_mesh(p), false, "two regions seed " + std::to_string(seed))
                            .interface_faces > 0;
    ++meshes[1];
    p.fracture = true;
    fracture_meshes += check_invariants(random_classified_mesh(p), false, "fracture seed " + std::to_string(seed))
                           .fracture_faces > 0;
    ++meshes[2];
    // Two sheets crossing along a line, one ending inside, one reaching the
    // outer boundary (two fracture model faces).
    p.regions = 1;
    p.crossing_sheet = true;
    crossing_meshes += check_invariants(random_classified_mesh(p), false, "crossing sheets seed " + std::to_string(seed))
                           .fracture_tags >= 2;
    ++meshes[4];
    // What real files carry beside the tets, dropped as a reader drops it:
    // the same dual as without it.
    p.crossing_sheet = false;
    p.unattached = true;
    {
      TetSoup soup = random_classified_mesh(p);
      io::drop_unattached(soup);
      unattached_meshes += soup.ignored.points >= 1 && soup.ignored.curves >= 2 && soup.ignored.surfaces >= 1 &&
                           soup.ignored.elements >= 5;
      check_invariants(soup, false, "unattached seed " + std::to_string(seed));
      RandomMeshParams clean = p;
      clean.unattached = false;
      const PolyMesh a = build_dual(classify(soup)), b = build_dual(classify(random_classified_mesh(clean)));
      EXPECT_TRUE(a.points == b.points && a.face_points == b.face_points && a.cell_offsets == b.cell_offsets &&
                  a.cell_primal == b.cell_primal)
          << "unattached seed " << seed;
    }
    ++meshes[5];
    p.unattached = false;
    p.fracture = false;
    p.lattice_points = true;
    merging_meshes += check_invariants(random_classified_mesh(p), true, "lattice seed " + std::to_string(seed))
                          .merged_points > 0;
    ++meshes[3];
    p.lattice_points = false;
    // Three crossing sheets (lines meeting at a point), fins attached to the
    // wall, a notch with concave model edges and vertex.
    {
      RandomMeshParams q = p;
      q.network = true;
      network_meshes += check_invariants(random_classified_mesh(q), false, "network seed " + std::to_string(seed))
                            .fracture_tags >= 3;
      q = p;
      q.fins = true;
      fin_meshes += check_invariants(random_classified_mesh(q), false, "fins seed " + std::to_string(seed))
                        .fracture_tags >= 2;
      q = p;
      q.notch = true;
      const TetSoup notched = random_classified_mesh(q);
      // Most of the octant (volume 1/8) is cut away, keeping the mesh manifold.
      double volume = 0;
      for (const auto& t : notched.tets) {
        const Point3 &a = notched.points[t[0]], &b = notched.points[t[1]], &c = notched.points[t[2]],
                     &d = notched.points[t[3]];
        volume += dot(b - a, cross(c - a, d - a)) / 6;
      }
      notch_meshes += volume < 1 - 0.125 * 0.6;
      check_invariants(notched, false, "notch seed " + std::to_string(seed));
      // Edges with several chains (proofs/edge_chains.md): every chain's fans
      // have their faces, so the cells at both ends stay closed.
      q = p;
      q.touching = true;
      touching_meshes += check_invariants(random_classified_mesh(q), false, "touching seed " + std::to_string(seed))
                             .multi_chain_edges > 0;
    }
    meshes[6] += 1, meshes[7] += 1, meshes[8] += 1, meshes[9] += 1;
    if (HasFailure()) break;
  }
  for (std::size_t n : meshes) EXPECT_EQ(n, 260u);  // 2600 meshes in all
  // Every two-region and fractured mesh has its interface/fracture faces;
  // the lattice points make cospherical neighbours in most lattice meshes
  // (177 of the 260 seeds).
  EXPECT_EQ(interface_meshes, 260u);
  EXPECT_EQ(fracture_meshes, 260u);
  EXPECT_GE(merging_meshes, 150u);
  EXPECT_GE(crossing_meshes, 200u);
  EXPECT_EQ(unattached_meshes, 260u);
  EXPECT_GE(network_meshes, 200u);
  EXPECT_GE(fin_meshes, 200u);
  EXPECT_GE(notch_meshes, 200u);
  EXPECT_GE(touching_meshes, 240u);
  // Some meshes have model faces touching at a vertex with no model edge
  // there (a fracture sheet touching the interface): that vertex is on the
  // dual too (checked above), so the families do exercise it.
  EXPECT_GT(g_touch_meshes, 0u);
  std::cout << "meshes with a model vertex on no model edge " << g_touch_meshes << "\n";
  std::cout << "three crossing sheets " << network_meshes << ", two fins " << fin_meshes
            << ", notched " << notch_meshes << ", touching along edges " << touching_meshes << " (of 260 each)\n";
  std::cout << "meshes with interface faces " << interface_meshes << ", fracture faces " << fracture_meshes
            << ", exact merges " << merging_meshes << ", two crossing sheets " << crossing_meshes
            << ", unattached entities dropped " << unattached_meshes << " (of 260 each)\n";
}

TEST(Dual, Deterministic) {
  RandomMeshParams p;
  p.seed = 7;
  p.num_points = 200;
  p.regions = 2;
  p.fracture = true;
  ClassifiedTetMesh m = classify(random_classified_mesh(p));
  PolyMesh a = build_dual(m), b = build_dual(m);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.face_points, b.face_points);
  EXPECT_EQ(a.cell_faces, b.cell_faces);
}

// ---- the stages on their own: build_dual_draft, cleanup_dual, assemble_cells

namespace {
// Every face of pm has >= 3 distinct points, all in range; every point is used.
void expect_compact(const PolyMesh& pm) {
  std::vector<char> used(pm.num_points(), 0);
  for (std::size_t f = 0; f < pm.num_faces(); ++f) {
    std::set<std::uint32_t> distinct;
    for (PointId p : pm.face(FaceId(f))) {
      ASSERT_LT(p.idx, pm.num_points());
      distinct.insert(p.idx);
      used[p.idx] = 1;
    }
    EXPECT_GE(distinct.size(), 3u) << "face " << f;
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
}
}  // namespace

// The Kuhn lattice 4x4x4: the six tets of each of the 64 cubes share the
// cube's circumsphere (centre on their common diagonal: well-centred), so the
// draft pairs them and the cleanup merges 5 centres per cube; the two boundary
// triangles of each of the 96 boundary squares are cocircular (centre on the
// diagonal): one merge each. The faces of the diagonals degenerate and are
// dropped; what is left are the boxes' faces: one quad per axis-parallel
// lattice edge (3 x 4 x 5 x 5 = 300) and one cap per boundary vertex and
// lattice side it lies on (6 x 25 = 150).
TEST(DualStages, CleanupMergesTheDraftsExactPairs) {
  ClassifiedTetMesh m = classify(kuhn_lattice(4, 4, 4));
  DualStats ds;
  DualDraft draft = build_dual_draft(m, {}, &ds);
  EXPECT_EQ(draft.num_cells, 125u);
  EXPECT_TRUE(draft.mesh.cell_faces.empty());
  EXPECT_EQ(draft.mesh.cell_material.size(), 125u);
  EXPECT_FALSE(draft.exact_pairs.empty());
  EXPECT_TRUE(std::is_sorted(draft.scan_faces.begin(), draft.scan_faces.end()));
  EXPECT_GT(draft.collapse_length, 0.0);
  const std::size_t raw_points = draft.mesh.num_points(), draft_faces = draft.mesh.num_faces();
  const CleanupStats cs = cleanup_dual(draft);
  EXPECT_EQ(cs.merged_points, 64u * 5u + 96u);
  EXPECT_EQ(cs.collapsed_points, 0u);
  EXPECT_EQ(draft.mesh.num_points(), raw_points - cs.merged_points);
  EXPECT_EQ(cs.dropped_points, cs.merged_points);  // each merged point is no face's any more
  EXPECT_TRUE(draft.exact_pairs.empty() && draft.short_pairs.empty() && draft.scan_faces.empty());
  expect_compact(draft.mesh);
  // The composition gives the same mesh as the stages.
  PolyMesh staged = assemble_cells(std::move(draft));
  PolyMesh composed = build_dual(m);
  EXPECT_EQ(staged.points, composed.points);
  EXPECT_EQ(staged.face_points, composed.face_points);
  EXPECT_EQ(staged.face_offsets, composed.face_offsets);
  EXPECT_EQ(staged.cell_faces, composed.cell_faces);
  EXPECT_EQ(staged.cell_offsets, composed.cell_offsets);
  EXPECT_EQ(count_boxes(staged), 125u);
  EXPECT_EQ(staged.num_faces(), 450u);
  EXPECT_EQ(staged.num_faces(), draft_faces - cs.dropped_faces);
}

// The collapse length is the draft's: the same draft with collapse_length 0
// collapses nothing (only the exact merge would run: none on a perturbed
// lattice), with it the tet centres of each cube collapse.
TEST(DualStages, CleanupCollapsesWithTheDraftsLength) {
  TetSoup s = kuhn_lattice(3, 3, 3);
  std::uint64_t state = 99;
  for (Point3& p : s.points)
    if (p.x > 0 && p.x < 3 && p.y > 0 && p.y < 3 && p.z > 0 && p.z < 3)
      for (int d = 0; d < 3; ++d) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        p[d] += (double(state >> 11) * 0x1p-53 - 0.5) * 2e-7;
      }
  ClassifiedTetMesh m = classify(s);
  DualDraft with = build_dual_draft(m), without = build_dual_draft(m);
  EXPECT_FALSE(with.short_pairs.empty());
  without.collapse_length = 0;
  const CleanupStats a = cleanup_dual(with), b = cleanup_dual(without);
  EXPECT_GT(a.collapsed_points, 0u);
  EXPECT_EQ(b.collapsed_points, 0u);
  EXPECT_LT(with.mesh.num_points(), without.mesh.num_points());
  expect_compact(with.mesh);
  expect_compact(without.mesh);
  // Without the cleanup the draft has no hints: cleanup_dual only compacts.
  DualParams off;
  off.cleanup = false;
  DualDraft raw = build_dual_draft(m, off);
  EXPECT_TRUE(raw.exact_pairs.empty() && raw.short_pairs.empty() && raw.scan_faces.empty());
  EXPECT_EQ(raw.collapse_length, 0.0);
  const CleanupStats c = cleanup_dual(raw);
  EXPECT_EQ(c.merged_points + c.collapsed_points, 0u);
}

// A hand-made draft: two triangles (0 1 2) and (0 3 1) with an exact pair
// (1, 3): the second degenerates to (0 1) and is dropped; points 3 (merged)
// and 4 (never used) are dropped and the survivors keep their order. A pair
// of different classifications (0, 2) is not merged, nor a short edge between
// them; the short edge (1, 2) of equal classes collapses into 1.
TEST(DualStages, CleanupOnAHandMadeDraft) {
  DualDraft d;
  const ModelRef in{3, 1}, on{2, 7};
  d.mesh.add_point({0, 0, 0}, on);
  d.mesh.add_point({1, 0, 0}, in);
  d.mesh.add_point({0, 1, 0}, in);
  d.mesh.add_point({1, 0, 0}, in);
  d.mesh.add_point({5, 5, 5}, in);
  d.mesh.add_point({0, 0, 1}, in);
  const PointId f0[] = {PointId(0), PointId(1), PointId(2)}, f1[] = {PointId(0), PointId(3), PointId(1)},
                f2[] = {PointId(0), PointId(2), PointId(5), PointId(1)};
  d.mesh.add_face(f0, CellId(0), CellId::invalid(), FaceKind::External, 7);
  d.mesh.add_face(f1, CellId(0), CellId::invalid(), FaceKind::External, 7);
  d.mesh.add_face(f2, CellId(0), CellId::invalid(), FaceKind::External, 7);
  d.num_cells = 1;
  d.mesh.cell_material = {1};
  d.mesh.cell_primal = {VertexId(0)};
  d.exact_pairs = {{PointId(1), PointId(3)}, {PointId(0), PointId(2)}};
  d.collapse_length = 2.0;  // every edge here is shorter
  d.scan_faces = {2};
  const CleanupStats st = cleanup_dual(d);
  EXPECT_EQ(st.merged_points, 1u);
  EXPECT_EQ(st.collapsed_points, 2u);  // 2 -> 1 and 5 -> 1 in face 2's loop; 0 is of another class
  EXPECT_EQ(st.dropped_faces, 3u);     // (0 1 1), (0 1), (0 1 1 1): all under 3 distinct points
  EXPECT_EQ(d.mesh.num_faces(), 0u);
  EXPECT_EQ(st.dropped_points, 6u);
  // Without the collapse only face 1 degenerates.
  DualDraft e;
  for (int i = 0; i < 6; ++i) e.mesh.add_point({double(i), 0, double(i % 2)}, i == 0 ? on : in);
  e.mesh.add_face(f0, CellId(0), CellId::invalid(), FaceKind::External, 7);
  e.mesh.add_face(f1, CellId(0), CellId::invalid(), FaceKind::Interface, 8);
  e.mesh.add_face(f2, CellId(0), CellId::invalid(), FaceKind::Fracture, 9);
  e.exact_pairs = {{PointId(1), PointId(3)}};
  const CleanupStats st2 = cleanup_dual(e);
  EXPECT_EQ(st2.merged_points, 1u);
  EXPECT_EQ(st2.dropped_faces, 1u);
  EXPECT_EQ(st2.dropped_points, 2u);  // 3 (merged into 1) and 4 (unused)
  ASSERT_EQ(e.mesh.num_faces(), 2u);
  EXPECT_EQ(e.mesh.face_tag, (std::vector<std::int32_t>{7, 9}));
  EXPECT_EQ(e.mesh.face_kind[1], FaceKind::Fracture);
  const auto loop = e.mesh.face(FaceId(1));
  EXPECT_EQ(std::vector<PointId>(loop.begin(), loop.end()),
            (std::vector<PointId>{PointId(0), PointId(2), PointId(3), PointId(1)}));  // 5 renumbered 3
  EXPECT_EQ(e.mesh.num_points(), 4u);
  expect_compact(e.mesh);
}

// validate(): a collapse tolerance outside [0, 0.5] throws UsageError naming
// the field, its unit and the range; build_dual refuses such params.
TEST(DualStages, ParamsValidateNamesFieldUnitAndRange) {
  ClassifiedTetMesh m = classify(kuhn_lattice(1, 1, 1));
  for (double bad : {-1e-9, 0.5000001, 3.0, std::nan("")}) {
    DualParams p;
    p.collapse_tolerance = bad;
    try {
      p.validate();
      FAIL() << "collapse_tolerance = " << bad << " accepted";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("collapse_tolerance"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("mean primal edge length"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("[0, 0.5]"), std::string::npos) << e.what();
    }
    EXPECT_THROW(build_dual(m, p), UsageError);
  }
  for (double good : {DualParams::kMinCollapseTolerance, 1e-3, DualParams::kMaxCollapseTolerance}) {
    DualParams p;
    p.collapse_tolerance = good;
    EXPECT_NO_THROW(p.validate()) << good;
  }
  DualParams p;
  p.cleanup = false;
  p.collapse_tolerance = 0.25;
  p.boundary = BoundaryMode::Caps;
  EXPECT_EQ(p.to_json().dump(0), "{\"boundary\":\"caps\",\"cleanup\":false,\"collapse_tolerance\":0.25}");
  CleanupStats cs;
  cs.merged_points = 3;
  EXPECT_NE(cs.to_json().dump(0).find("\"merged_points\":3"), std::string::npos);
}

// The caps' centre of a model-face triangle (dual/central_points.h): the
// circumcentre of an acute triangle; the centroid when the angle opposite an
// edge on a model edge is right or obtuse (the circumcentre, or the clamped
// point, would lie on the model edge and flatten the cap face there); the
// plain rule when that edge is not on a model edge.
TEST(DualCentres, CapTriangleCentreLeavesModelEdges) {
  const bool none[3] = {false, false, false}, edge_c[3] = {false, false, true};
  const Point3 a{0, 0, 0}, b{2, 0, 0};
  // Acute: the circumcentre, whatever the flags.
  const Point3 acute{1, 1.5, 0};
  EXPECT_EQ(cap_triangle_point(a, b, acute, edge_c).p, triangle_central_point(a, b, acute).p);
  EXPECT_TRUE(cap_triangle_point(a, b, acute, edge_c).well_centred);
  // Right angle at the apex (1, 1): circumcentre (1, 0, 0) on the edge ab.
  const Point3 right{1, 1, 0};
  EXPECT_EQ(triangle_central_point(a, b, right).p, (Point3{1, 0, 0}));
  const CentralPoint r = cap_triangle_point(a, b, right, edge_c);
  EXPECT_FALSE(r.well_centred);
  EXPECT_NEAR(r.p.y, 1.0 / 3, 1e-15);
  EXPECT_EQ(cap_triangle_point(a, b, right, none).p, (Point3{1, 0, 0}));
  // Obtuse at the apex: the clamped point lands on ab (y == 0) unless ab is a model edge.
  const Point3 obtuse{1, 0.3, 0};
  EXPECT_EQ(triangle_central_point(a, b, obtuse).p.y, 0.0);
  EXPECT_NEAR(cap_triangle_point(a, b, obtuse, edge_c).p.y, 0.1, 1e-15);
}
