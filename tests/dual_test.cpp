// Dual construction (SPEC §4) and its invariants (SPEC §10) on Kuhn lattices
// and random classified tet meshes.
#include <gtest/gtest.h>

#include <CGAL/Gmpq.h>

#include <map>
#include <set>

#include "classify/classify.h"
#include "dual/build_dual.h"
#include "generate/random_mesh.h"
#include "mesh/validate.h"
#include "quality/star_test.h"

using namespace polydual;

namespace {

// Exact sum of decomposition volumes (x6) per material, with rational means.
std::map<std::int32_t, CGAL::Gmpq> exact_material_volumes(const PolyMesh& pm) {
  using Q = CGAL::Gmpq;
  struct QV { Q x, y, z; };
  auto mean = [&](const std::vector<PointId>& pts) {
    QV s{Q(0), Q(0), Q(0)};
    for (PointId p : pts) { s.x += Q(pm.points[p.idx].x); s.y += Q(pm.points[p.idx].y); s.z += Q(pm.points[p.idx].z); }
    Q n(int(pts.size()));
    return QV{s.x / n, s.y / n, s.z / n};
  };
  auto qv = [&](PointId p) { return QV{Q(pm.points[p.idx].x), Q(pm.points[p.idx].y), Q(pm.points[p.idx].z)}; };
  auto det = [](const QV& a, const QV& b, const QV& c) {
    return a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
  };
  std::map<std::int32_t, Q> vol;
  for (std::size_t c = 0; c < pm.num_cells(); ++c) {
    QV R = mean(pm.cell_points(CellId(c)));
    Q sum(0);
    for (HalfFace h : pm.cell(CellId(c))) {
      auto loop = pm.oriented_loop(h);
      QV F = mean(loop);
      for (std::size_t k = 0; k < loop.size(); ++k) {
        QV a = qv(loop[k]), b = qv(loop[(k + 1) % loop.size()]);
        sum += det({a.x - R.x, a.y - R.y, a.z - R.z}, {b.x - R.x, b.y - R.y, b.z - R.z},
                   {F.x - R.x, F.y - R.y, F.z - R.z});
      }
    }
    vol[pm.cell_material[c]] += sum;
  }
  return vol;
}

std::map<std::int32_t, CGAL::Gmpq> exact_primal_volumes(const ClassifiedTetMesh& m) {
  using Q = CGAL::Gmpq;
  std::map<std::int32_t, Q> vol;
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const auto& v = m.tet(TetId(t));
    auto P = [&](int i) { return m.point(v[i]); };
    Q ux = Q(P(1).x) - Q(P(0).x), uy = Q(P(1).y) - Q(P(0).y), uz = Q(P(1).z) - Q(P(0).z);
    Q vx = Q(P(2).x) - Q(P(0).x), vy = Q(P(2).y) - Q(P(0).y), vz = Q(P(2).z) - Q(P(0).z);
    Q wx = Q(P(3).x) - Q(P(0).x), wy = Q(P(3).y) - Q(P(0).y), wz = Q(P(3).z) - Q(P(0).z);
    vol[m.region(TetId(t))] += ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) + uz * (vx * wy - vy * wx);
  }
  return vol;
}

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

void check_invariants(const TetSoup& soup, bool planar, const std::string& what) {
  SCOPED_TRACE(what);
  ClassifiedTetMesh m = classify(soup);
  PolyMesh pm = build_dual(m);
  ValidationReport r = validate(pm, &m);
  EXPECT_EQ(r.face_errors, 0u);
  EXPECT_EQ(r.closed_cells, r.cells);
  // Known limitation (lib/dual/build_dual.cpp, make_caps): a model vertex where a
  // single model edge ends inside a model face is not represented, and so a
  // model edge both of whose model vertices are such has no dual edge along
  // it. Anything else missing is a failure.
  for (const std::string& miss : r.missing_model_entities) {
    bool dangling = false;
    if (miss.rfind("model edge ", 0) == 0) {
      const int tag = std::stoi(miss.substr(11));
      dangling = true;
      for (const ModelEntity& v : m.model().entities[0])
        if (std::count(v.bounds.begin(), v.bounds.end(), tag))
          dangling &= std::count(r.missing_model_entities.begin(), r.missing_model_entities.end(),
                                 "model vertex " + std::to_string(v.tag)) == 1;
    }
    if (miss.rfind("model vertex ", 0) == 0) {
      const int tag = std::stoi(miss.substr(13));
      for (std::size_t v = 0; v < m.num_vertices(); ++v) {
        if (m.vertex_class(VertexId(v)) != ModelRef{0, tag}) continue;
        int model_edges = 0;
        for (std::size_t e = 0; e < m.num_edges(); ++e)
          if (m.edge_class(EdgeId(e)).dim == 1 && (m.edge(EdgeId(e))[0] == VertexId(v) || m.edge(EdgeId(e))[1] == VertexId(v)))
            ++model_edges;
        dangling = model_edges == 1;
      }
    }
    EXPECT_TRUE(dangling) << miss;
  }
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
    if (std::count(r.missing_model_entities.begin(), r.missing_model_entities.end(), name)) continue;
    bool found = false;
    for (std::size_t p = 0; p < pm.num_points() && !found; ++p)
      found = pm.point_class[p] == m.vertex_class(VertexId(v)) && pm.points[p] == m.point(VertexId(v));
    EXPECT_TRUE(found) << "model vertex at primal vertex " << v;
  }
  if (planar) {
    auto dv = exact_material_volumes(pm);
    auto pv = exact_primal_volumes(m);
    ASSERT_EQ(dv.size(), pv.size());
    for (auto& [tag, q] : pv) EXPECT_TRUE(dv[tag] == q) << "material " << tag << ": dual " << CGAL::to_double(dv[tag]) / 6 << " primal " << CGAL::to_double(q) / 6;
  }
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
  // 1000+ random classified meshes: one region (planar faces: exact volume
  // identity), two regions (jagged interface), with fracture, lattice points.
  int n = 0;
  for (std::uint64_t seed = 1; seed <= 260; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 20 + int(seed % 30);
    check_invariants(random_classified_mesh(p), true, "single seed " + std::to_string(seed));
    p.regions = 2;
    check_invariants(random_classified_mesh(p), false, "two regions seed " + std::to_string(seed));
    p.fracture = true;
    check_invariants(random_classified_mesh(p), false, "fracture seed " + std::to_string(seed));
    p.regions = 1;
    p.fracture = false;
    p.lattice_points = true;
    check_invariants(random_classified_mesh(p), true, "lattice seed " + std::to_string(seed));
    n += 4;
    if (HasFailure()) break;
  }
  EXPECT_GE(n, 1000);
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
