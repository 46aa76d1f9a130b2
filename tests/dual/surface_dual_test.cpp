// The surface dual (dual/surface_dual.h) and its exact checks
// (quality/surface_verdict.h) on planar squares, a fracture network, a closed
// cube surface and a sphere, quads and a mixed triangle/quad surface.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "classify/classify_primal.h"
#include "core/error.h"
#include "dual/central_points.h"
#include "dual/surface_dual.h"
#include "generate/fracture_surfaces.h"
#include "mesh/cell_soup.h"
#include "predicates/predicates.h"
#include "quality/surface_verdict.h"

using namespace polydual;
using ::testing::HasSubstr;

namespace {

PrimalMesh primal_of(const TetSoup& soup) { return build_primal(cell_soup(soup)); }

// Per undirected dual edge, the polygons using it with their direction.
struct EdgeUse {
  std::size_t polygon;
  bool forward;  // runs from the smaller point id to the larger
};
std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<EdgeUse>> dual_edges(const PolySurface& s) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<EdgeUse>> out;
  for (std::size_t i = 0; i < s.num_polygons(); ++i) {
    const auto p = s.polygon(i);
    for (std::size_t k = 0; k < p.size(); ++k) {
      const std::uint32_t a = p[k], b = p[(k + 1) % p.size()];
      out[{std::min(a, b), std::max(a, b)}].push_back({i, a < b});
    }
  }
  return out;
}

bool on_curve(const PolySurface& s, std::uint32_t p) { return s.point_class(p).dim <= 1; }

// Each dual edge is used by exactly two polygons of one surface, in opposite
// directions, or both its points lie on model curves (boundary, crossing);
// with `closed`, every edge by exactly two polygons. Returns the edges checked.
std::size_t expect_conformal(const PolySurface& s, bool closed) {
  const auto edges = dual_edges(s);
  for (const auto& [e, uses] : edges) {
    if (!closed && on_curve(s, e.first) && on_curve(s, e.second)) {
      EXPECT_GE(uses.size(), 1u);
      continue;
    }
    EXPECT_EQ(uses.size(), 2u) << "dual edge " << e.first << "-" << e.second;
    if (uses.size() != 2) continue;
    EXPECT_NE(uses[0].forward, uses[1].forward) << "dual edge " << e.first << "-" << e.second;
    if (!closed) EXPECT_EQ(s.surface(uses[0].polygon), s.surface(uses[1].polygon));
  }
  return edges.size();
}

void expect_all_valid(const PolySurface& s) {
  const SurfaceVerdicts v = surface_verdicts(s);
  EXPECT_EQ(v.invalid, 0u);
  EXPECT_GT(v.fan_triangles, 2 * s.num_polygons());
}

TetSoup unit_square(int n) { return lattice_rectangles_soup({{2, 0, 0, 0, 2 * n, 0, 2 * n, 1}}, n, "<square>"); }

}  // namespace

TEST(SurfaceDual, PlanarSquareIsTheVoronoiDiagramOfItsDelaunayVertices) {
  const PrimalMesh m = primal_of(unit_square(8));
  const PolySurface s = build_surface_dual(m);
  expect_all_valid(s);
  expect_conformal(s, false);
  const SurfaceAreaIdentity a = surface_area_identity(m, s);
  ASSERT_EQ(a.surfaces.size(), 1u);
  EXPECT_TRUE(a.surfaces.at(1).planar);
  EXPECT_NEAR(a.surfaces.at(1).primal, 1.0, 1e-15);
  EXPECT_LE(a.max_rel_error, 1e-12);  // floating point sums (1e-12 relative)
  std::size_t interior = 0;
  for (std::size_t i = 0; i < s.num_polygons(); ++i) {
    const VertexId v(std::size_t(s.primal_vertex(i)));
    if (m.vertex_class(v).dim != 2) continue;
    ++interior;
    // The Voronoi cell: exactly the circumcentres of v's triangles.
    const auto p = s.polygon(i);
    ASSERT_EQ(p.size(), m.vertex_cells(v).size());
    std::set<std::uint32_t> cells;
    for (std::uint32_t q : p) {
      ASSERT_EQ(s.point_origin(q).kind, SurfacePointOrigin::Kind::CellCentre);
      const auto cv = m.cell_vertices(PrimalCellId(std::size_t(s.point_origin(q).id)));
      const CentralPoint c = triangle_central_point(m.point(cv[0]), m.point(cv[1]), m.point(cv[2]));
      EXPECT_TRUE(c.well_centred);  // the lattice is acute: the centre is the circumcentre
      EXPECT_EQ(s.point(q), c.p);
      EXPECT_NEAR(norm(c.p - m.point(cv[0])), norm(c.p - m.point(cv[1])), 1e-14);
      cells.insert(s.point_origin(q).id);
    }
    const auto star = m.vertex_cells(v);
    EXPECT_EQ(cells.size(), star.size());
    for (PrimalCellId c : star) EXPECT_TRUE(cells.count(c.idx));
  }
  EXPECT_GT(interior, 40u);
}

TEST(SurfaceDual, PlanarFanTestIsOrient2dInThePlane) {
  const PolySurface s = build_surface_dual(primal_of(unit_square(4)));
  std::size_t checked = 0;
  for (std::size_t i = 0; i < s.num_polygons(); ++i) {
    const auto p = s.polygon(i);
    const auto n = s.fan_normals(i);
    const Point3& r = s.reference(i);
    for (std::size_t k = 0; k < p.size(); ++k) {
      const Point3 &a = s.point(p[k]), &b = s.point(p[(k + 1) % p.size()]);
      ASSERT_EQ(n[k].x, 0.0);
      ASSERT_EQ(n[k].y, 0.0);
      ASSERT_EQ(n[k].z, 1.0);
      EXPECT_EQ(surface_turn(r, a, b, n[k]), orient2d(r.x, r.y, a.x, a.y, b.x, b.y));
      ++checked;
    }
  }
  EXPECT_GT(checked, 100u);
  // A fan triangle turned clockwise is negative: the test can fail.
  EXPECT_EQ(surface_turn({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}), Sign::Negative);
  EXPECT_EQ(surface_turn({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), Sign::Positive);
  EXPECT_EQ(surface_turn({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 1}), Sign::Zero);
}

TEST(SurfaceDual, AMovedCentreMakesItsPolygonsInvalid) {
  const PrimalMesh m = primal_of(unit_square(4));
  PolySurface s = build_surface_dual(m);
  // Reflect one centre of an interior polygon through its primal vertex: a
  // fan triangle next to it turns clockwise (the polygon's angular steps are
  // under half a turn).
  std::size_t polygon = 0;
  while (m.vertex_class(VertexId(std::size_t(s.primal_vertex(polygon)))).dim != 2) ++polygon;
  ASSERT_TRUE(surface_polygon_valid(s, polygon));
  const std::uint32_t q = s.polygon(polygon)[0];
  s.set_point(q, 2.0 * s.reference(polygon) - s.point(q));
  EXPECT_FALSE(surface_polygon_valid(s, polygon));
  EXPECT_GE(surface_verdicts(s).invalid, 1u);
}

TEST(SurfaceDual, FractureNetworkPolygonsOnEachSideAreConformalAndTileEachSurface) {
  const PrimalMesh m = primal_of(fracture_network_surface(8));
  const PolySurface s = build_surface_dual(m);
  expect_all_valid(s);
  EXPECT_GT(expect_conformal(s, false), 1000u);
  const SurfaceAreaIdentity a = surface_area_identity(m, s);
  ASSERT_EQ(a.surfaces.size(), 3u);
  EXPECT_EQ(a.planar, 3u);
  EXPECT_NEAR(a.surfaces.at(1).primal, 4.0, 1e-13);
  EXPECT_NEAR(a.surfaces.at(2).primal, 4.0, 1e-13);
  EXPECT_NEAR(a.surfaces.at(3).primal, 0.5, 1e-13);
  EXPECT_LE(a.max_rel_error, 1e-12);
  // Polygons per primal vertex: 4 on the F1 x F2 crossing line and on the
  // F1 x F3 segment (two sides in each sheet), 3 at the segment's end inside
  // F1 (F1's polygon closes around it, with the crossing edge's midpoint once).
  std::map<std::uint64_t, std::vector<std::size_t>> of_vertex;
  for (std::size_t i = 0; i < s.num_polygons(); ++i) of_vertex[s.primal_vertex(i)].push_back(i);
  auto vertex_at = [&](Point3 p) {
    for (std::size_t v = 0; v < m.num_vertices(); ++v)
      if (m.point(VertexId(v)) == p) return std::uint64_t(v);
    ADD_FAILURE() << "no vertex at " << p.x << " " << p.y << " " << p.z;
    return std::uint64_t(0);
  };
  EXPECT_EQ(of_vertex[vertex_at({0.5, 0, 0})].size(), 4u);
  EXPECT_EQ(of_vertex[vertex_at({0.5, 0.5, 0})].size(), 4u);
  const auto end = of_vertex[vertex_at({0.25, 0.5, 0})];
  ASSERT_EQ(end.size(), 3u);
  std::size_t closing = 0;
  for (std::size_t i : end) {
    if (s.surface(i) != 1) continue;
    ++closing;
    std::size_t mids = 0, vertices = 0;
    for (std::uint32_t q : s.polygon(i)) {
      mids += s.point_origin(q).kind == SurfacePointOrigin::Kind::EdgeMidpoint;
      vertices += s.point_origin(q).kind == SurfacePointOrigin::Kind::Vertex;
    }
    EXPECT_EQ(mids, 1u);
    EXPECT_EQ(vertices, 0u);
  }
  EXPECT_EQ(closing, 1u);
  // The crossing line's midpoints are shared by the four polygons around it.
  std::map<std::uint32_t, std::set<std::int32_t>> surfaces_of_point;
  for (std::size_t i = 0; i < s.num_polygons(); ++i)
    for (std::uint32_t q : s.polygon(i)) surfaces_of_point[q].insert(s.surface(i));
  std::size_t crossing_mids = 0;
  for (std::size_t q = 0; q < s.num_points(); ++q)
    if (s.point_origin(q).kind == SurfacePointOrigin::Kind::EdgeMidpoint && surfaces_of_point[q].size() == 2)
      ++crossing_mids;
  EXPECT_EQ(crossing_mids, 16u + 4u);  // 16 edges on F1 x F2, 4 on F1 x F3
}

TEST(SurfaceDual, NumberingIsDeterministic) {
  const PrimalMesh m = primal_of(fracture_network_surface(4));
  const PolySurface a = build_surface_dual(m), b = build_surface_dual(m);
  ASSERT_EQ(a.num_polygons(), b.num_polygons());
  ASSERT_EQ(a.points(), b.points());
  for (std::size_t i = 0; i < a.num_polygons(); ++i) {
    EXPECT_TRUE(std::ranges::equal(a.polygon(i), b.polygon(i)));
    if (i > 0) EXPECT_LE(a.primal_vertex(i - 1), a.primal_vertex(i));
  }
}

namespace {

// The six faces of the cube [0, 1]^3, each outward (counterclockwise in (s, t)
// about the outward normal e_s x e_t).
TetSoup cube_surface(int n) {
  const int L = 2 * n;
  return lattice_rectangles_soup({{0, 0, 2, 0, L, 0, L, 1}, {0, L, 1, 0, L, 0, L, 2},
                                  {1, 0, 0, 0, L, 0, L, 3}, {1, L, 2, 0, L, 0, L, 4},
                                  {2, 0, 1, 0, L, 0, L, 5}, {2, L, 0, 0, L, 0, L, 6}},
                                 n, "<cube surface>");
}

// An icosahedron subdivided `levels` times, projected on the unit sphere.
TetSoup sphere(int levels) {
  TetSoup soup;
  soup.source = "<sphere>";
  const double g = (1 + std::sqrt(5.0)) / 2;
  soup.points = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                 {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<std::uint32_t, 3>> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                                  {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                  {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                                  {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto [it, fresh] = mid.emplace(key, std::uint32_t(soup.points.size()));
      if (fresh) soup.points.push_back(0.5 * (soup.points[a] + soup.points[b]));
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto& t : f) {
      const std::uint32_t a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), c = midpoint(t[2], t[0]);
      next.push_back({t[0], a, c});
      next.push_back({t[1], b, a});
      next.push_back({t[2], c, b});
      next.push_back({a, b, c});
    }
    f = std::move(next);
  }
  for (Point3& p : soup.points) p = p / norm(p);
  for (const auto& t : f) soup.triangles.push_back({t, 1});
  return soup;
}

}  // namespace

TEST(SurfaceDual, ClosedCubeSurfaceEveryDualEdgeInTwoPolygons) {
  const PrimalMesh m = primal_of(cube_surface(4));
  const PolySurface s = build_surface_dual(m);
  expect_all_valid(s);
  expect_conformal(s, true);
  // One polygon per vertex, but 2 at each of the 3 vertices inside a cube
  // edge (one per face) and 3 at a corner.
  EXPECT_EQ(s.num_polygons(), m.num_vertices() + 12 * 3 + 8 * 2);
  const SurfaceAreaIdentity a = surface_area_identity(m, s);
  EXPECT_EQ(a.planar, 6u);
  EXPECT_LE(a.max_rel_error, 1e-12);
}

TEST(SurfaceDual, ClosedSphereOnePolygonPerVertexAllValid) {
  const PrimalMesh m = primal_of(sphere(3));
  const PolySurface s = build_surface_dual(m);
  EXPECT_EQ(s.num_polygons(), m.num_vertices());
  EXPECT_EQ(s.num_points(), m.num_cells());  // only cell centres: no curve, no vertex point
  expect_all_valid(s);
  expect_conformal(s, true);
  const SurfaceAreaIdentity a = surface_area_identity(m, s);
  EXPECT_EQ(a.planar, 0u);
  EXPECT_LE(a.max_rel_error_all, 1e-2);  // a measure on a curved surface, not an identity
}

namespace {

// Quadrangles of side 2u on rows t in [-2 rows, 0) below a lattice triangle
// strip on [0, 4u) (non-offset row at t = 0): a mixed planar surface.
TetSoup quad_grid(int n, int quad_rows, bool with_triangles) {
  TetSoup soup = with_triangles ? lattice_rectangles_soup({{2, 0, 0, 0, 2 * n, 0, 8, 1}}, n, "<mixed>") : TetSoup{};
  soup.source = "<quads>";
  std::map<std::pair<int, int>, std::uint32_t> index;
  for (std::size_t p = 0; p < soup.points.size(); ++p)
    index[{int(std::lround(soup.points[p].x * 2 * n)), int(std::lround(soup.points[p].y * 2 * n))}] = std::uint32_t(p);
  auto point = [&](int s, int t) {
    const auto [it, fresh] = index.emplace(std::pair{s, t}, std::uint32_t(soup.points.size()));
    if (fresh) soup.points.push_back({s / (2.0 * n), t / (2.0 * n), 0});
    return it->second;
  };
  for (int t = -2 * quad_rows; t < 0; t += 2)
    for (int s = 0; s < 2 * n; s += 2)
      soup.quads.push_back({{point(s, t), point(s + 2, t), point(s + 2, t + 2), point(s, t + 2)}, 1});
  return soup;
}

}  // namespace

TEST(SurfaceDual, QuadGridIsDualToItsShiftedGrid) {
  const PrimalMesh m = primal_of(quad_grid(4, 8, false));
  const PolySurface s = build_surface_dual(m);
  expect_all_valid(s);
  expect_conformal(s, false);
  EXPECT_LE(surface_area_identity(m, s).max_rel_error, 1e-12);
  for (std::size_t i = 0; i < s.num_polygons(); ++i)
    if (m.vertex_class(VertexId(std::size_t(s.primal_vertex(i)))).dim == 2) EXPECT_EQ(s.polygon(i).size(), 4u);
}

TEST(SurfaceDual, CocircularTrianglesShareTheirCentre) {
  // Squares split along one diagonal: the two right triangles of a square
  // have one circumcentre; it becomes one dual point, so the dual is the
  // shifted square grid, valid, with no dual edge of length zero.
  TetSoup quads = quad_grid(4, 4, false), soup;
  soup.source = "<right triangles>";
  soup.points = quads.points;
  for (const TaggedQuad& q : quads.quads) {
    soup.triangles.push_back({{q.v[0], q.v[1], q.v[2]}, 1});
    soup.triangles.push_back({{q.v[0], q.v[2], q.v[3]}, 1});
  }
  const PrimalMesh m = primal_of(soup);
  const PolySurface s = build_surface_dual(m);
  std::size_t centres = 0;
  for (std::size_t q = 0; q < s.num_points(); ++q) centres += s.point_origin(q).kind == SurfacePointOrigin::Kind::CellCentre;
  EXPECT_EQ(centres, quads.quads.size());
  expect_all_valid(s);
  expect_conformal(s, false);
  for (const auto& [e, uses] : dual_edges(s)) EXPECT_NE(s.point(e.first), s.point(e.second));
  EXPECT_LE(surface_area_identity(m, s).max_rel_error, 1e-12);
  for (std::size_t i = 0; i < s.num_polygons(); ++i)
    if (m.vertex_class(VertexId(std::size_t(s.primal_vertex(i)))).dim == 2) EXPECT_EQ(s.polygon(i).size(), 4u);
}

TEST(SurfaceDual, MixedTriangleQuadSurface) {
  const PrimalMesh m = primal_of(quad_grid(4, 3, true));
  ASSERT_GT(m.num_cells(), 24u);
  const PolySurface s = build_surface_dual(m);
  expect_all_valid(s);
  expect_conformal(s, false);
  EXPECT_LE(surface_area_identity(m, s).max_rel_error, 1e-12);
}

TEST(SurfaceDual, InconsistentOrientationNamesTheCells) {
  TetSoup soup;
  soup.source = "flipped.msh";
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  soup.triangles = {{{0, 1, 2}, 1}, {{1, 2, 3}, 1}};  // both run 1 -> 2
  const PrimalMesh m = primal_of(soup);
  try {
    build_surface_dual(m);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("flipped.msh"));
    EXPECT_THAT(e.what(), HasSubstr("triangle 1 and triangle 2"));
    EXPECT_THAT(e.what(), HasSubstr("orientation is inconsistent"));
  }
}

TEST(SurfaceDual, DegenerateTriangleIsNamed) {
  TetSoup soup;
  soup.source = "flat.msh";
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
  soup.triangles = {{{0, 1, 2}, 1}, {{0, 3, 1}, 1}};
  try {
    primal_of(soup);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("flat.msh: triangle 2"));
    EXPECT_THAT(e.what(), HasSubstr("degenerate"));
  }
}
