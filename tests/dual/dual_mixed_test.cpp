// The dual of a PrimalMesh (dual/primal_dual.h): on tet meshes the same
// cells as the tet builder (the strongest check of its rules), and on hex,
// prism and pyramid meshes closed, valid cells with the expected volumes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include <tbb/task_arena.h>

#include "classify/classify.h"
#include "classify/classify_primal.h"
#include "dual/build_dual.h"
#include "dual/primal_dual.h"
#include "generate/random_mesh.h"
#include "generate/random_mixed.h"
#include "mesh/cell_soup.h"
#include "mesh/model_facets.h"
#include "mesh/validate.h"
#include "optim/optimize.h"
#include "quality/check_result.h"

namespace polydual {
namespace {

// The tet soup of a classified tet mesh with its whole classification given
// (model faces, edges and vertices with their tags, internal numbering), so
// that build_primal() classifies it as classify() did.
TetSoup classified_soup(const ClassifiedTetMesh& m) {
  TetSoup s;
  s.source = "classified";
  s.points = m.points();
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const auto& v = m.tet(TetId(t));
    s.tets.push_back({v[0].idx, v[1].idx, v[2].idx, v[3].idx});
    s.tet_region.push_back(m.region(TetId(t)));
  }
  for (std::size_t f = 0; f < m.num_triangles(); ++f)
    if (m.on_model_face(TriId(f))) {
      const auto& v = m.triangle(TriId(f));
      s.triangles.push_back({{v[0].idx, v[1].idx, v[2].idx}, m.triangle_class(TriId(f)).tag});
    }
  for (std::size_t e = 0; e < m.num_edges(); ++e)
    if (m.edge_class(EdgeId(e)).dim == 1)
      s.edges.push_back({{m.edge(EdgeId(e))[0].idx, m.edge(EdgeId(e))[1].idx}, m.edge_class(EdgeId(e)).tag});
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (m.vertex_class(VertexId(v)).dim == 0) s.corners.push_back({std::uint32_t(v), m.vertex_class(VertexId(v)).tag});
  return s;
}

// A cell seen from outside its numbering: its volume and its points' sorted coordinates.
struct CellPrint {
  double volume = 0;
  std::vector<Point3> points;
};

std::vector<Point3> cell_points(const PolyMesh& pm, CellId c) {
  std::vector<Point3> pts;
  for (std::uint32_t h = pm.cell_offsets[c.idx]; h < pm.cell_offsets[c.idx + 1]; ++h) {
    const FaceId f = pm.cell_faces[h].face();
    for (std::uint32_t k = pm.face_offsets[f.idx]; k < pm.face_offsets[f.idx + 1]; ++k)
      pts.push_back(pm.points[pm.face_points[k].idx]);
  }
  auto less = [](const Point3& a, const Point3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  };
  std::sort(pts.begin(), pts.end(), less);
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  return pts;
}

// Per primal vertex (by `vertex_of` of its cell_primal), its cells sorted by volume.
std::map<std::uint32_t, std::vector<CellPrint>> prints(const PolyMesh& pm, const std::vector<VertexId>& vertex_of) {
  std::map<std::uint32_t, std::vector<CellPrint>> out;
  for (std::size_t c = 0; c < pm.num_cells(); ++c)
    out[vertex_of.empty() ? pm.cell_primal[c].idx : vertex_of[pm.cell_primal[c].idx].idx].push_back(
        {cell_volume(pm, CellId(c)), cell_points(pm, CellId(c))});
  for (auto& [v, cells] : out)
    std::sort(cells.begin(), cells.end(), [](const CellPrint& a, const CellPrint& b) { return a.volume < b.volume; });
  return out;
}

void expect_same_dual(const PolyMesh& tet, const PolyMesh& mixed, const ClassifiedTetMesh& m, const std::string& what) {
  ASSERT_EQ(tet.num_cells(), mixed.num_cells()) << what;
  ASSERT_EQ(tet.num_faces(), mixed.num_faces()) << what;
  EXPECT_EQ(tet.num_points(), mixed.num_points()) << what;
  const auto a = prints(tet, internal_of_input(m)), b = prints(mixed, {});
  ASSERT_EQ(a.size(), b.size()) << what;
  for (const auto& [v, cells] : a) {
    const auto& other = b.at(v);
    ASSERT_EQ(cells.size(), other.size()) << what << " vertex " << v;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      // Relative to the cell's volume, or to the box's for a sliver cell whose
      // volume is a cancelling sum (the same points give volumes of 1e-11
      // differing by 1e-20 when the cell's faces start their loops elsewhere).
      EXPECT_NEAR(cells[k].volume, other[k].volume, 1e-12 * std::max(std::fabs(cells[k].volume), 1e-6))
          << what << " vertex " << v;
      ASSERT_EQ(cells[k].points.size(), other[k].points.size()) << what << " vertex " << v;
      for (std::size_t p = 0; p < cells[k].points.size(); ++p)
        EXPECT_LT(norm(cells[k].points[p] - other[k].points[p]), 1e-12) << what << " vertex " << v;
    }
  }
}

RandomMeshParams family(std::uint64_t seed) {
  RandomMeshParams p;
  p.seed = seed;
  p.num_points = 60 + int(seed % 3) * 40;
  p.regions = seed % 2 == 0 ? 2 : 1;
  p.fracture = seed % 3 != 0;
  p.crossing_sheet = seed % 5 == 1;
  p.network = seed % 7 == 3;
  p.fins = seed % 4 == 2;
  p.notch = seed % 6 == 4;
  p.lattice_points = seed % 8 == 5;
  p.touching = seed % 6 == 5;  // edges of several chains (never with the notch: seed % 6 == 4)
  return p;
}

TEST(DualMixed, SameDualAsTheTetBuilderOnRandomMeshes) {
  for (std::uint64_t seed = 1; seed <= 18; ++seed)
    for (bool cleanup : {false, true})
      for (BoundaryMode mode : {BoundaryMode::Caps, BoundaryMode::Keep}) {
        const ClassifiedTetMesh m = classify(random_classified_mesh(family(seed)));
        const PrimalMesh pm = build_primal(cell_soup(classified_soup(m)));
        DualParams dp;
        dp.cleanup = cleanup;
        dp.boundary = mode;
        const std::string what = "seed " + std::to_string(seed) + (cleanup ? " cleanup" : " raw") + " " +
                                 boundary_mode_name(mode);
        expect_same_dual(build_dual(m, dp), build_primal_dual(pm, dp), m, what);
      }
}

// --- structured mixed meshes of the unit box (n cells a side, h = 1/n;
// add_cell and tag_box_boundary from generate/random_mixed.h)

struct Grid {
  int n;
  std::uint32_t id(int i, int j, int k) const { return std::uint32_t((k * (n + 1) + j) * (n + 1) + i); }
};

TetSoup grid_points(int n) {
  TetSoup s;
  s.source = "grid";
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) s.points.push_back({double(i) / n, double(j) / n, double(k) / n});
  return s;
}

std::vector<std::uint32_t> cube(const Grid& g, int i, int j, int k) {
  return {g.id(i, j, k),         g.id(i + 1, j, k),         g.id(i + 1, j + 1, k),     g.id(i, j + 1, k),
          g.id(i, j, k + 1),     g.id(i + 1, j, k + 1),     g.id(i + 1, j + 1, k + 1), g.id(i, j + 1, k + 1)};
}

// n^3 hexahedra, region 1 where x < 1/2 and 2 elsewhere.
TetSoup hex_block_soup(int n) {
  TetSoup s = grid_points(n);
  const Grid g{n};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) add_cell(s, CellType::Hex, cube(g, i, j, k), 2 * i < n ? 1 : 2);
  tag_box_boundary(s, 0, 1);
  return s;
}

// Each cube's square (i, j) split into two triangles; the bottom layer k = 0
// is prisms (a boundary layer), the others each prism cut into three tets,
// every quadrangle split along the diagonal from its smallest vertex (so
// neighbours agree: the classic conformal rule).
TetSoup prism_layer_soup(int n) {
  TetSoup s = grid_points(n);
  const Grid g{n};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& tri : {std::array<std::array<int, 2>, 3>{{{0, 0}, {1, 0}, {1, 1}}},
                                std::array<std::array<int, 2>, 3>{{{0, 0}, {1, 1}, {0, 1}}}}) {
          std::vector<std::uint32_t> p;
          for (int z = 0; z < 2; ++z)
            for (const auto& c : tri) p.push_back(g.id(i + c[0], j + c[1], k + z));
          if (k == 0) { add_cell(s, CellType::Prism, p, 1); continue; }
          // Rotate the prism so that its smallest vertex is bottom vertex 0 (or top 3): then
          // the three tets (0 1 2 m), ... follow the smallest-vertex rule on every side quad.
          const std::uint32_t lo = *std::min_element(p.begin(), p.end());
          int r = 0;
          while (p[r] != lo && p[r + 3] != lo) ++r;
          std::vector<std::uint32_t> q{p[r], p[(r + 1) % 3], p[(r + 2) % 3], p[3 + r], p[3 + (r + 1) % 3],
                                       p[3 + (r + 2) % 3]};
          if (q[3] == lo) q = {q[3], q[4], q[5], q[0], q[1], q[2]};
          // Vertex 0 is the smallest, so the side quads through it split from it; the third,
          // (1 2 5 4), along 1-5 or 2-4, whichever holds its smallest vertex.
          if (std::min(q[1], q[5]) < std::min(q[2], q[4])) {
            add_cell(s, CellType::Tet, {q[0], q[1], q[2], q[5]}, 2);
            add_cell(s, CellType::Tet, {q[0], q[1], q[5], q[4]}, 2);
          } else {
            add_cell(s, CellType::Tet, {q[0], q[1], q[2], q[4]}, 2);
            add_cell(s, CellType::Tet, {q[0], q[2], q[5], q[4]}, 2);
          }
          add_cell(s, CellType::Tet, {q[0], q[4], q[5], q[3]}, 2);
        }
  tag_box_boundary(s, 0, 1);
  return s;
}

// Hexahedra below z = 1/2, tets above, joined through pyramids, unjittered
// (generate/random_mixed.h).
TetSoup hex_pyramid_tet_soup(int n) { return random_hex_pyramid_tets(0, n, 0.0); }

// Closed cells, sound faces, every cell star-shaped by the exact test (after
// the default optimiser on the primal's model facets when `optimise`), and
// the cells' volumes summing to `volume`.
void expect_sound(PolyMesh pm, double volume, const std::string& what, const PrimalMesh* optimise = nullptr) {
  if (optimise) {
    const ModelFacets facets = model_facets(*optimise);
    optimize(pm, &facets, OptimParams{});
  }
  const CheckResult c = check_mesh(pm, nullptr);
  EXPECT_EQ(c.validation.closed_cells, pm.num_cells()) << what;
  EXPECT_EQ(c.validation.face_errors, 0u) << what;
  EXPECT_EQ(c.invalid_cells, 0u) << what;
  double sum = 0;
  for (std::size_t k = 0; k < pm.num_cells(); ++k) sum += cell_volume(pm, CellId(k));
  EXPECT_NEAR(sum, volume, 1e-12) << what;
}

TEST(DualMixed, HexBlockTwoMaterials) {
  const int n = 4;
  const PrimalMesh m = build_primal(cell_soup(hex_block_soup(n)));
  for (BoundaryMode mode : {BoundaryMode::Caps, BoundaryMode::Keep}) {
    DualParams dp;
    dp.boundary = mode;
    const PolyMesh pm = build_primal_dual(m, dp);
    EXPECT_EQ(pm.num_cells(), std::size_t((n + 1) * (n + 1) * (n + 1)) + (n + 1) * (n + 1)) << "the interface doubles its vertices";
    expect_sound(pm, 1.0, boundary_mode_name(mode));
    std::map<std::int32_t, double> by_material;
    for (std::size_t c = 0; c < pm.num_cells(); ++c) by_material[pm.cell_material[c]] += cell_volume(pm, CellId(c));
    EXPECT_NEAR(by_material[1], 0.5, 1e-12);
    EXPECT_NEAR(by_material[2], 0.5, 1e-12);
    // The vertex (1, 1, 1)/n is interior: its cell is the cube of the 8 hex centres, side 1/n.
    const double h = 1.0 / n;
    for (std::size_t c = 0; c < pm.num_cells(); ++c) {
      if (pm.cell_primal[c].idx != Grid{n}.id(1, 1, 1)) continue;
      EXPECT_NEAR(cell_volume(pm, CellId(c)), h * h * h, 1e-15);
      const auto pts = cell_points(pm, CellId(c));
      ASSERT_EQ(pts.size(), 8u);
      for (const Point3& p : pts)
        for (int d = 0; d < 3; ++d) EXPECT_TRUE(p[d] == 0.5 * h || p[d] == 1.5 * h) << p[d];
    }
  }
}

TEST(DualMixed, PrismLayerOnTets) {
  const PrimalMesh m = build_primal(cell_soup(prism_layer_soup(4)));
  for (BoundaryMode mode : {BoundaryMode::Caps, BoundaryMode::Keep}) {
    DualParams dp;
    dp.boundary = mode;
    const PolyMesh pm = build_primal_dual(m, dp);
    EXPECT_GT(pm.num_cells(), 125u);  // the prism/tet interface doubles its 25 vertices
    expect_sound(pm, 1.0, std::string("prism layer ") + boundary_mode_name(mode));
  }
}

TEST(DualMixed, HexesJoinedToTetsThroughPyramids) {
  const TetSoup soup = hex_pyramid_tet_soup(4);
  const auto counts = mixed_cell_counts(soup);
  EXPECT_EQ(counts[std::size_t(CellType::Pyramid)], 16u);
  const PrimalMesh m = build_primal(cell_soup(soup));
  for (BoundaryMode mode : {BoundaryMode::Caps, BoundaryMode::Keep}) {
    DualParams dp;
    dp.boundary = mode;
    // The tets from the cubes' centres have their circumcentres on their
    // faces or outside (clamped): the raw dual has cells that are not
    // star-shaped (57 caps, 32 keep), which the optimiser repairs.
    expect_sound(build_primal_dual(m, dp), 1.0, std::string("pyramids ") + boundary_mode_name(mode), &m);
  }
}

// The model facetisation of a PrimalMesh: each model-face quadrangle is two
// triangles with its face id, and every dual point made from a face or edge
// on a model entity finds its facet by PointOrigin id.
TEST(DualMixed, ModelFacetsOfAPrimalMesh) {
  const PrimalMesh m = build_primal(cell_soup(hex_block_soup(3)));
  const ModelFacets f = model_facets(m);
  std::size_t quads = 0;
  for (std::size_t i = 0; i < m.num_faces(); ++i) quads += m.face_class(PrimalFaceId(i)).dim == 2;
  EXPECT_EQ(f.triangles.size(), 2 * quads);  // every face is a quadrangle
  EXPECT_EQ(quads, 6u * 9 + 9);              // the box's 54 and the interface's 9
  EXPECT_EQ(f.segments.size(), 12u * 3 + 4 * 3);  // the box's edges and the interface's rim
  for (std::size_t k = 0; k + 1 < f.triangles.size(); ++k) EXPECT_LE(f.triangles[k].src, f.triangles[k + 1].src);
  const PolyMesh pm = build_primal_dual(m);
  for (std::size_t p = 0; p < pm.num_points(); ++p) {
    const PointOrigin o = pm.point_origin[p];
    if (o.dim != 1 && o.dim != 2) continue;
    const auto& list = o.dim == 2 ? f.triangles : f.segments;
    const auto it = std::find_if(list.begin(), list.end(), [&](const ModelFacet& x) { return x.src == o.id; });
    ASSERT_NE(it, list.end()) << "point " << p;
    EXPECT_EQ(it->tag, pm.point_class[p].tag) << "point " << p;
  }
}

// Whole cuts (the mixed split): any set of vertices cut whole leaves every
// cell closed, every face sound and the volume exact, in both modes (the
// neighbours' faces pass through the corners' points); a vertex cut whole has
// one cell per primal cell round it; with every vertex cut, the cells are
// the barycentric corners, convex on a hex-pyramid-tet block: all valid.
TEST(DualMixed, WholeCutsStayConformalAndCutEveryCorner) {
  RandomMeshParams p;
  p.seed = 3;
  p.num_points = 40;
  p.face_points = 6;
  p.regions = 2;
  p.fracture = true;
  const double h = 0.05 + 0.065;
  const std::pair<TetSoup, double> meshes[] = {{random_hex_pyramid_tets(5, 4, 0.2), 1.0},
                                               {random_prism_layers(p, 2, 0.05, 1.3), std::pow(1 + 2 * h, 3)}};
  for (const auto& [soup, volume] : meshes) {
    const PrimalMesh m = build_primal(cell_soup(soup));
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      std::vector<char> whole(m.num_vertices(), 0);
      std::size_t k = 0;
      for (auto& w : whole) w = char((k++ * 2654435761u + seed * 97u) % 10 < 3);  // about 30 %
      for (BoundaryMode mode : {BoundaryMode::Caps, BoundaryMode::Keep}) {
        DualParams dp;
        dp.boundary = mode;
        const PolyMesh pm = build_primal_dual(m, dp, nullptr, &whole);
        const std::string what = std::string(soup.source) + " seed " + std::to_string(seed) + " " + boundary_mode_name(mode);
        const CheckResult c = check_mesh(pm, nullptr);
        EXPECT_EQ(c.validation.closed_cells, pm.num_cells()) << what;
        EXPECT_EQ(c.validation.face_errors, 0u) << what;
        double sum = 0;
        std::map<std::uint32_t, std::size_t> per_vertex;
        for (std::size_t q = 0; q < pm.num_cells(); ++q) {
          sum += cell_volume(pm, CellId(q));
          ++per_vertex[pm.cell_primal[q].idx];
        }
        EXPECT_NEAR(sum, volume, 1e-12 * volume) << what;
        for (std::size_t v = 0; v < m.num_vertices(); ++v)
          if (whole[v]) EXPECT_EQ(per_vertex[std::uint32_t(m.input_vertex(VertexId(v)))], m.vertex_cells(VertexId(v)).size()) << what;
      }
    }
  }
  const PrimalMesh block = build_primal(cell_soup(random_hex_pyramid_tets(5, 4, 0.2)));
  const std::vector<char> all(block.num_vertices(), 1);
  const PolyMesh pm = build_primal_dual(block, DualParams{}, nullptr, &all);
  EXPECT_EQ(check_mesh(pm, nullptr).invalid_cells, 0u);
  std::size_t corners = 0;
  for (std::size_t c = 0; c < block.num_cells(); ++c) corners += block.cell_vertices(PrimalCellId(c)).size();
  EXPECT_EQ(pm.num_cells(), corners);
}

// The same dual, byte for byte, on one thread and on all of them.
TEST(DualMixed, DeterministicForAnyThreadCount) {
  const PrimalMesh m = build_primal(cell_soup(hex_pyramid_tet_soup(4)));
  const PolyMesh all = build_primal_dual(m);
  tbb::task_arena one(1);
  const PolyMesh single = one.execute([&] { return build_primal_dual(m); });
  EXPECT_EQ(all.points, single.points);
  EXPECT_EQ(all.face_points, single.face_points);
  EXPECT_EQ(all.face_offsets, single.face_offsets);
  EXPECT_EQ(all.face_owner, single.face_owner);
  EXPECT_EQ(all.face_neighbour, single.face_neighbour);
  EXPECT_EQ(all.cell_offsets, single.cell_offsets);
}

}  // namespace
}  // namespace polydual
