// The dual builder with per-vertex virtual cut surfaces (dual/vertex_cuts.h,
// design §8; the rules and lemmas: proofs/dual_cuts.md): random proper cut
// sets (tets of a vertex's star labelled by a random plane or random labels,
// every non-model triangle between two labels cut) and the fallback cut (every
// non-model triangle at the vertex: one cell per tet) on random classified
// meshes; a fracture tip cut by the extension of its sheet.
#include <gtest/gtest.h>

#include <CGAL/Gmpq.h>

#include <algorithm>
#include <iostream>
#include <numeric>
#include <random>
#include <set>

#include "classify/classify.h"
#include "core/error.h"
#include "dual/build_dual.h"
#include "exact_volume.h"
#include "generate/random_mesh.h"
#include "mesh/validate.h"
#include "quality/star_verdict.h"

using namespace polydual;

namespace {

// Calls f(t, s, f) for each triangle through v between two tets t, s of v's
// star, once per triangle (from its smaller tet).
template <class F>
void for_each_star_triangle(const ClassifiedTetMesh& m, VertexId v, F&& f) {
  for (TetId t : m.vertex_tets(v))
    for (int j = 0; j < 4; ++j) {
      if (m.tet(t)[j] == v) continue;
      const TetId s = m.tet_neighbor(t, j);
      if (s.valid() && s.idx > t.idx) f(t, s, m.tet_triangle(t, j));
    }
}

Point3 centroid(const ClassifiedTetMesh& m, TetId t) {
  const auto& v = m.tet(t);
  return 0.25 * (m.point(v[0]) + m.point(v[1]) + m.point(v[2]) + m.point(v[3]));
}

// Cuts of the vertices in `vs`: label(v, t) per star tet; every non-model
// triangle at v between tets of different labels is cut.
template <class Label>
VertexCuts label_cuts(const ClassifiedTetMesh& m, const std::vector<VertexId>& vs, Label&& label) {
  std::vector<std::pair<VertexId, TriId>> pairs;
  for (VertexId v : vs)
    for_each_star_triangle(m, v, [&](TetId t, TetId s, TriId f) {
      if (!m.on_model_face(f) && label(v, t) != label(v, s)) pairs.emplace_back(v, f);
    });
  return VertexCuts::from_pairs(m.num_vertices(), std::move(pairs));
}

VertexCuts fallback_cuts(const ClassifiedTetMesh& m, const std::vector<VertexId>& vs) {
  std::vector<std::pair<VertexId, TriId>> pairs;
  for (VertexId v : vs)
    for_each_star_triangle(m, v, [&](TetId, TetId, TriId f) {
      if (!m.on_model_face(f)) pairs.emplace_back(v, f);
    });
  return VertexCuts::from_pairs(m.num_vertices(), std::move(pairs));
}

// Independent count of the sides: per vertex a union-find over its star,
// joined across triangles on no model face and not in its cuts.
std::size_t count_sides(const ClassifiedTetMesh& m, const VertexCuts& cuts) {
  std::size_t total = 0;
  for (std::size_t vi = 0; vi < m.num_vertices(); ++vi) {
    const VertexId v(vi);
    const auto star = m.vertex_tets(v);
    std::vector<std::size_t> parent(star.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](std::size_t x) {
      while (parent[x] != x) x = parent[x];
      return x;
    };
    auto pos = [&](TetId t) { return std::size_t(std::find(star.begin(), star.end(), t) - star.begin()); };
    for_each_star_triangle(m, v, [&](TetId t, TetId s, TriId f) {
      if (m.on_model_face(f) || cuts.cuts(v, f)) return;
      parent[find(pos(t))] = find(pos(s));
    });
    for (std::size_t k = 0; k < star.size(); ++k) total += find(k) == k;
  }
  return total;
}

std::size_t slit_faces(const PolyMesh& pm) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < pm.num_faces(); ++f) n += pm.face_owner[f] == pm.face_neighbour[f];
  return n;
}

bool same_mesh(const PolyMesh& a, const PolyMesh& b) {
  return a.points == b.points && a.point_class == b.point_class && a.point_origin == b.point_origin &&
         a.face_offsets == b.face_offsets && a.face_points == b.face_points && a.face_owner == b.face_owner &&
         a.face_neighbour == b.face_neighbour && a.face_kind == b.face_kind && a.face_tag == b.face_tag &&
         a.cell_offsets == b.cell_offsets && a.cell_faces == b.cell_faces && a.cell_material == b.cell_material &&
         a.cell_primal == b.cell_primal;
}

// point_origin names an entity of the right kind, and the point is
// classified on it or (a point cuts add) on an entity of higher dimension.
void check_origins(const ClassifiedTetMesh& m, const PolyMesh& pm) {
  ASSERT_EQ(pm.point_origin.size(), pm.num_points());
  for (std::size_t p = 0; p < pm.num_points(); ++p) {
    const PointOrigin o = pm.point_origin[p];
    const ModelRef c = pm.point_class[p];
    ASSERT_TRUE(o.dim >= 0 && o.dim <= 3) << "point " << p;
    const std::size_t n[4] = {m.num_vertices(), m.num_edges(), m.num_triangles(), m.num_tets()};
    ASSERT_LT(o.id, n[o.dim]) << "point " << p;
    ModelRef own = o.dim == 3   ? ModelRef{3, m.region(TetId(o.id))}
                   : o.dim == 2 ? m.triangle_class(TriId(o.id))
                   : o.dim == 1 ? m.edge_class(EdgeId(o.id))
                                : m.vertex_class(VertexId(o.id));
    if (o.dim == 2 && !m.on_model_face(TriId(o.id))) own = ModelRef{3, m.region(m.triangle_tet(TriId(o.id), 0))};
    EXPECT_EQ(c, own) << "point " << p << " origin dim " << int(o.dim) << " id " << o.id;
  }
}

struct CutRun {
  std::size_t cells = 0, cut_cells = 0;  // cells of cut vertices
  std::size_t valid_cut_cells = 0;       // of those, star-shaped (exact) at the initial positions
};

// Builds the dual with `cuts` and checks it against the one without.
CutRun check_cuts(const ClassifiedTetMesh& m, const VertexCuts& cuts, bool planar, const std::string& what) {
  SCOPED_TRACE(what);
  CutRun run;
  const PolyMesh base = build_dual(m);
  DualStats st;
  const PolyMesh pm = build_dual(m, {}, &st, &cuts);
  const ValidationReport r = validate(pm, &m), r0 = validate(base, &m);
  EXPECT_EQ(r.face_errors, 0u);
  EXPECT_EQ(r.closed_cells, r.cells);
  EXPECT_EQ(r.misoriented_cells, 0u);
  // What the dual without cuts misses (a known limitation, dual_test.cpp),
  // and nothing else.
  for (const std::string& miss : r.missing_model_entities)
    EXPECT_TRUE(std::count(r0.missing_model_entities.begin(), r0.missing_model_entities.end(), miss)) << miss;
  EXPECT_EQ(pm.num_cells(), count_sides(m, cuts));
  EXPECT_GE(pm.num_cells(), base.num_cells());
  // Proper cuts create no slit cell: a cut triangle separates two sides.
  // (A slit cap of another vertex may be split in two at a new stop edge.)
  EXPECT_LE(r.slit_cells, r0.slit_cells);
  for (std::size_t f = 0; f < pm.num_faces(); ++f)
    EXPECT_EQ(pm.face_kind[f] == FaceKind::External, !pm.face_neighbour[f].valid()) << "face " << f;
  check_origins(m, pm);
  if (planar) {
    auto dv = polydual::testing::exact_dual_volumes(pm);
    auto pv = polydual::testing::exact_primal_volumes(m);
    EXPECT_EQ(dv.size(), pv.size());
    for (auto& [tag, q] : pv) EXPECT_TRUE(dv[tag] == q) << "material " << tag;
  }
  std::set<std::uint32_t> cut_vertices;
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (!cuts.of(VertexId(v)).empty()) cut_vertices.insert(m.input_vertex(VertexId(v)));
  run.cells = pm.num_cells();
  for (std::size_t c = 0; c < pm.num_cells(); ++c) {
    if (!cut_vertices.count(pm.cell_primal[c].idx)) continue;
    ++run.cut_cells;
    run.valid_cut_cells += star_shaped_verdict(pm, CellId(c)).valid;
  }
  return run;
}

// Random vertices: every vertex with probability 1/4, and one vertex of each
// classification dimension present (model vertex, edge, face, region).
std::vector<VertexId> pick_vertices(const ClassifiedTetMesh& m, std::mt19937_64& rng) {
  std::vector<VertexId> vs;
  bool have[4] = {false, false, false, false};
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const int dim = m.vertex_class(VertexId(v)).dim;
    // Vertices on model faces and edges are few: picked more often.
    if ((rng() & (dim == 1 || dim == 2 ? 1 : 3)) == 0 || !have[dim]) {
      vs.push_back(VertexId(v));
      have[dim] = true;
    }
  }
  return vs;
}

struct Tally {
  std::size_t meshes = 0, builds = 0, fallback_by_dim[4] = {0, 0, 0, 0}, adjacent_fallback = 0;
  std::size_t fallback_cells = 0, fallback_valid = 0, fallback_cells_by_dim[4] = {0, 0, 0, 0},
              fallback_valid_by_dim[4] = {0, 0, 0, 0};
  std::size_t extra_cells = 0;
};

void run_mesh(const TetSoup& soup, bool planar, std::uint64_t seed, const std::string& what, Tally& tally) {
  const ClassifiedTetMesh m = classify(soup);
  std::mt19937_64 rng(seed * 7919 + 13);
  ++tally.meshes;
  // No cuts (null, empty, offsets without triangles): the same mesh.
  {
    const PolyMesh a = build_dual(m);
    VertexCuts none;
    none.off.assign(m.num_vertices() + 1, 0);
    EXPECT_TRUE(same_mesh(a, build_dual(m, {}, nullptr, &none))) << what;
    const VertexCuts empty;
    EXPECT_TRUE(same_mesh(a, build_dual(m, {}, nullptr, &empty))) << what;
    check_origins(m, a);
  }
  // A random plane through each picked vertex.
  {
    std::vector<VertexId> vs = pick_vertices(m, rng);
    std::vector<Vec3> normal(m.num_vertices());
    std::normal_distribution<double> g;
    for (VertexId v : vs) normal[v.idx] = Vec3{g(rng), g(rng), g(rng)};
    const VertexCuts cuts = label_cuts(m, vs, [&](VertexId v, TetId t) {
      return dot(centroid(m, t) - m.point(v), normal[v.idx]) > 0;
    });
    const CutRun r = check_cuts(m, cuts, planar, what + " plane cuts");
    tally.extra_cells += r.cells - build_dual(m).num_cells();
    ++tally.builds;
  }
  // Two or three random labels per star tet.
  {
    std::vector<VertexId> vs = pick_vertices(m, rng);
    const std::uint64_t salt = rng(), k = 2 + rng() % 2;
    const VertexCuts cuts = label_cuts(m, vs, [&](VertexId v, TetId t) {
      std::uint64_t h = (std::uint64_t(v.idx) * 0x9e3779b97f4a7c15ull) ^ (std::uint64_t(t.idx) + salt);
      h ^= h >> 29;
      h *= 0xbf58476d1ce4e5b9ull;
      h ^= h >> 32;
      return h % k;
    });
    check_cuts(m, cuts, planar, what + " label cuts");
    ++tally.builds;
  }
  // The fallback on picked vertices, and on both ends of a random edge.
  {
    std::vector<VertexId> vs = pick_vertices(m, rng);
    const auto ends = m.edge(EdgeId(rng() % m.num_edges()));
    vs.push_back(ends[0]);
    vs.push_back(ends[1]);
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    const VertexCuts cuts = fallback_cuts(m, vs);
    const CutRun r = check_cuts(m, cuts, planar, what + " fallback cuts");
    ++tally.builds;
    ++tally.adjacent_fallback;
    for (VertexId v : vs) ++tally.fallback_by_dim[m.vertex_class(v).dim];
    tally.fallback_cells += r.cut_cells;
    tally.fallback_valid += r.valid_cut_cells;
    // Per dimension of the vertex (the verdicts again, per cell).
    const PolyMesh pm = build_dual(m, {}, nullptr, &cuts);
    std::vector<int> dim_of_input(m.num_vertices(), -1);
    for (VertexId v : vs) dim_of_input[m.input_vertex(v)] = m.vertex_class(v).dim;
    for (std::size_t c = 0; c < pm.num_cells(); ++c) {
      const int dim = dim_of_input[pm.cell_primal[c].idx];
      if (dim < 0) continue;
      ++tally.fallback_cells_by_dim[dim];
      tally.fallback_valid_by_dim[dim] += star_shaped_verdict(pm, CellId(c)).valid;
    }
  }
}

}  // namespace

TEST(DualCuts, RandomProperAndFallbackCuts) {
  // 4 families x 60 seeds = 240 meshes, each with plane cuts, random-label
  // cuts and the fallback (720 cut duals).
  Tally tally;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 20 + int(seed % 30);
    run_mesh(random_classified_mesh(p), true, seed, "single seed " + std::to_string(seed), tally);
    p.regions = 2;
    run_mesh(random_classified_mesh(p), false, seed, "two regions seed " + std::to_string(seed), tally);
    p.fracture = true;
    run_mesh(random_classified_mesh(p), false, seed, "fracture seed " + std::to_string(seed), tally);
    p.regions = 1;
    p.crossing_sheet = true;
    run_mesh(random_classified_mesh(p), false, seed, "crossing seed " + std::to_string(seed), tally);
    if (HasFailure()) break;
  }
  EXPECT_EQ(tally.meshes, 240u);
  EXPECT_EQ(tally.builds, 720u);
  // Vertices on model edges and faces are rare in these meshes (58 and 25
  // fallback vertices); model vertices and interior ones are not.
  const std::size_t at_least[4] = {1000, 50, 20, 1000};
  for (int d = 0; d < 4; ++d)
    EXPECT_GE(tally.fallback_by_dim[d], at_least[d]) << "fallback at vertices of dim " << d;
  EXPECT_GT(tally.extra_cells, 1000u);  // the plane cuts did split stars
  std::cout << "fallback cut vertices by dim (0..3): " << tally.fallback_by_dim[0] << " " << tally.fallback_by_dim[1]
            << " " << tally.fallback_by_dim[2] << " " << tally.fallback_by_dim[3] << "; plane cuts added "
            << tally.extra_cells << " cells\n";
  std::cout << "fallback cells star-shaped at initial positions: " << tally.fallback_valid << " of "
            << tally.fallback_cells << "; by vertex dim:";
  for (int d = 0; d < 4; ++d)
    std::cout << " dim " << d << " " << tally.fallback_valid_by_dim[d] << "/" << tally.fallback_cells_by_dim[d];
  std::cout << "\n";
}

// A fracture tip vertex whose slit cell is cut by the extension of its sheet
// (random fracture meshes: the sheet separates tets whose centroids lie on
// opposite sides of z = 0.5; the extension cuts the rest of v's star the same
// way): the slit face at v disappears and v has two cells.
TEST(DualCuts, FractureTipCutBySheetExtension) {
  std::size_t tips = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 40;
    p.fracture = true;
    const ClassifiedTetMesh m = classify(random_classified_mesh(p));
    const PolyMesh base = build_dual(m);
    std::vector<VertexId> input_to_internal(m.num_vertices());
    for (std::size_t v = 0; v < m.num_vertices(); ++v) input_to_internal[m.input_vertex(VertexId(v))] = VertexId(v);
    std::set<std::uint32_t> slit_vertices;  // internal ids
    for (std::size_t f = 0; f < base.num_faces(); ++f)
      if (base.face_owner[f] == base.face_neighbour[f])
        slit_vertices.insert(input_to_internal[base.cell_primal[base.face_owner[f].idx].idx].idx);
    auto below = [&](TetId t) { return centroid(m, t).z < 0.5; };
    for (std::uint32_t vi : slit_vertices) {
      const VertexId v(vi);
      // Only vertices whose star is one region and whose two halves are
      // each connected (then the cut gives exactly two sides).
      const auto star = m.vertex_tets(v);
      if (std::any_of(star.begin(), star.end(), [&](TetId t) { return m.region(t) != m.region(star[0]); })) continue;
      VertexCuts halves = label_cuts(m, {v}, [&](VertexId, TetId t) { return below(t); });
      std::vector<std::pair<VertexId, TriId>> sheet;
      for_each_star_triangle(m, v, [&](TetId t, TetId s, TriId f) {
        if (below(t) != below(s)) sheet.emplace_back(v, f);
      });
      VertexCuts all_halves = VertexCuts::from_pairs(m.num_vertices(), sheet);  // with the model triangles
      std::size_t sides = 0;
      {
        std::vector<std::size_t> parent(star.size());
        std::iota(parent.begin(), parent.end(), 0);
        auto find = [&](std::size_t x) {
          while (parent[x] != x) x = parent[x];
          return x;
        };
        auto pos = [&](TetId t) { return std::size_t(std::find(star.begin(), star.end(), t) - star.begin()); };
        for_each_star_triangle(m, v, [&](TetId t, TetId s, TriId f) {
          if (!all_halves.cuts(v, f) && !m.on_model_face(f)) parent[find(pos(t))] = find(pos(s));
        });
        for (std::size_t k = 0; k < star.size(); ++k) sides += find(k) == k;
      }
      if (sides != 2 || halves.empty()) continue;
      ++tips;
      const PolyMesh pm = build_dual(m, {}, nullptr, &halves);
      const ValidationReport r = validate(pm, &m);
      EXPECT_TRUE(r.ok()) << "seed " << seed << " vertex " << vi;
      std::size_t cells_of_v = 0;
      for (std::size_t c = 0; c < pm.num_cells(); ++c) cells_of_v += pm.cell_primal[c].idx == m.input_vertex(v);
      EXPECT_EQ(cells_of_v, 2u) << "seed " << seed << " vertex " << vi;
      for (std::size_t f = 0; f < pm.num_faces(); ++f)
        if (pm.face_owner[f] == pm.face_neighbour[f])
          EXPECT_NE(pm.cell_primal[pm.face_owner[f].idx].idx, m.input_vertex(v))
              << "slit face left at seed " << seed << " vertex " << vi;
      EXPECT_LT(slit_faces(pm), slit_faces(base));
    }
  }
  EXPECT_GE(tips, 10u);
  std::cout << "fracture tip vertices cut by the sheet's extension: " << tips << "\n";
}

// Bad cut sets are an error naming the mesh and the vertex, not a crash.
TEST(DualCuts, BadCutSetsAreErrors) {
  RandomMeshParams p;
  p.seed = 3;
  p.num_points = 20;
  const ClassifiedTetMesh m = classify(random_classified_mesh(p));
  // A boundary triangle (on a model face) and a triangle not through the vertex.
  TriId boundary = TriId::invalid(), interior = TriId::invalid();
  for (std::size_t f = 0; f < m.num_triangles(); ++f)
    (m.on_model_face(TriId(f)) ? boundary : interior) = TriId(f);
  ASSERT_TRUE(boundary.valid() && interior.valid());
  const VertexId on_boundary = m.triangle(boundary)[0];
  auto expect_error = [&](const VertexCuts& c, const std::string& text) {
    try {
      build_dual(m, {}, nullptr, &c);
      ADD_FAILURE() << "no error for " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("vertex cuts"), std::string::npos) << e.what();
    }
  };
  expect_error(VertexCuts::from_pairs(m.num_vertices(), {{on_boundary, boundary}}), "on a model face");
  VertexId away = VertexId::invalid();
  for (std::size_t v = 0; v < m.num_vertices() && !away.valid(); ++v) {
    const auto t = m.triangle(interior);
    if (std::find(t.begin(), t.end(), VertexId(v)) == t.end()) away = VertexId(v);
  }
  expect_error(VertexCuts::from_pairs(m.num_vertices(), {{away, interior}}), "does not contain the vertex");
  VertexCuts short_off = VertexCuts::from_pairs(m.num_vertices() - 1, {});
  short_off.tri.push_back(interior);
  short_off.off.back() = 1;
  expect_error(short_off, "offsets");
  // Offsets that run past the list (read before any triangle of the vertex).
  VertexCuts past = VertexCuts::from_pairs(m.num_vertices(), {});
  past.tri = {interior, interior};
  past.off.assign(m.num_vertices() + 1, 2);
  past.off[0] = 0;
  past.off[1] = 5;
  expect_error(past, "offsets past the triangle list");
  // A triangle listed twice, a triangle that does not exist.
  const VertexId a = m.triangle(interior)[0];
  VertexCuts twice = VertexCuts::from_pairs(m.num_vertices(), {{a, interior}});
  twice.tri.push_back(interior);
  for (std::size_t v = a.idx + 1; v < twice.off.size(); ++v) ++twice.off[v];
  expect_error(twice, "triangles not increasing");
  VertexCuts none = VertexCuts::from_pairs(m.num_vertices(), {{a, interior}});
  none.tri[0] = TriId(std::uint32_t(m.num_triangles()));
  expect_error(none, "no such triangle");
  // Several bad vertices (checked in parallel): the error names the first.
  std::vector<std::pair<VertexId, TriId>> bad;
  VertexId first_bad = VertexId::invalid();
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const auto t = m.triangle(interior);
    if (std::find(t.begin(), t.end(), VertexId(v)) != t.end()) continue;
    if (!first_bad.valid()) first_bad = VertexId(v);
    bad.emplace_back(VertexId(v), interior);
  }
  ASSERT_GE(bad.size(), 2u);
  const VertexCuts many = VertexCuts::from_pairs(m.num_vertices(), bad);
  try {
    build_dual(m, {}, nullptr, &many);
    ADD_FAILURE() << "no error for several bad vertices";
  } catch (const InputError& e) {
    const std::string want = "vertex cuts of vertex " + std::to_string(m.input_vertex(first_bad)) + ",";
    EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
  }
}
