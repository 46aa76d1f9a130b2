// build_surface_dual: sides of each vertex, then one polygon per side.
#include "dual/surface_dual.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/union_find.h"
#include "dual/primal_central_points.h"
#include "predicates/predicates.h"

namespace polydual {
namespace {

// v's neighbours in cell c's loop: the loop runs prev -> v -> next.
struct Corner {
  VertexId next, prev;
};
Corner corner_at(const PrimalMesh& m, PrimalCellId c, VertexId v) {
  const auto cv = m.cell_vertices(c);
  const std::size_t n = cv.size(), i = std::size_t(m.local_index(c, v));
  return {cv[(i + 1) % n], cv[(i + n - 1) % n]};
}

bool on_curve(const PrimalMesh& m, EdgeId e) { return m.edge_class(e).dim != 2; }

// "triangle 12": the k-th cell of its type (1-based), as cell_place names
// the soup's cells (errors only: it counts).
std::string cell_name(const PrimalMesh& m, PrimalCellId c) {
  std::size_t k = 1;
  for (std::size_t i = 0; i < c.idx; ++i) k += m.cell_type(PrimalCellId(i)) == m.cell_type(c);
  return std::string(m.cell_descriptor(c).name) + " " + std::to_string(k);
}

// The other cell of an edge on no model curve (it has exactly two). `c2`
// must continue c's orientation: its loop runs the edge the other way.
PrimalCellId across(const PrimalMesh& m, EdgeId e, PrimalCellId c, VertexId v, bool forward) {
  const auto cs = m.edge_cells(e);
  const PrimalCellId c2 = cs[0] == c ? cs[1] : cs[0];
  const Corner a = corner_at(m, c, v), b = corner_at(m, c2, v);
  if (forward ? b.next != a.prev : b.prev != a.next) {
    const auto [x, y] = m.edge(e);
    throw InputError(m.source(), cell_name(m, c),
                     cell_name(m, c) + " and " + cell_name(m, c2) + " of surface " +
                         std::to_string(m.cell_class(c).tag) + " run their common edge (" +
                         std::to_string(m.input_vertex(x) + 1) + " " + std::to_string(m.input_vertex(y) + 1) +
                         ") the same way: the surface's orientation is inconsistent there");
  }
  return c2;
}

struct Side {
  std::vector<PrimalCellId> cells;  // counterclockwise about v
  bool closed = false;
  EdgeId first, last;  // open sides: the curve edges before cells.front() and after cells.back()
};

// From `seed`, back (clockwise) to the cell after a curve edge; `seed` itself
// when the fan closes.
std::pair<PrimalCellId, bool> side_start(const PrimalMesh& m, VertexId v, PrimalCellId seed) {
  PrimalCellId c = seed;
  for (std::size_t steps = 0; steps <= m.vertex_cells(v).size(); ++steps) {
    const EdgeId e = m.find_edge(v, corner_at(m, c, v).next);
    if (on_curve(m, e)) return {c, false};
    c = across(m, e, c, v, false);
    if (c == seed) return {seed, true};
  }
  throw std::logic_error("surface dual: a fan around a vertex does not end");
}

std::vector<Side> vertex_sides(const PrimalMesh& m, VertexId v) {
  const auto star = m.vertex_cells(v);
  std::vector<char> placed(star.size(), 0);
  std::vector<Side> sides;
  for (std::size_t i = 0; i < star.size(); ++i) {
    if (placed[i]) continue;
    Side s;
    const auto [start, closed] = side_start(m, v, star[i]);
    s.closed = closed;
    s.first = m.find_edge(v, corner_at(m, start, v).next);
    for (PrimalCellId c = start;;) {
      s.cells.push_back(c);
      placed[std::size_t(std::lower_bound(star.begin(), star.end(), c) - star.begin())] = 1;
      const EdgeId e = m.find_edge(v, corner_at(m, c, v).prev);
      if (on_curve(m, e)) {
        s.last = e;
        break;
      }
      c = across(m, e, c, v, true);
      if (c == start || s.cells.size() > star.size()) break;
    }
    sides.push_back(std::move(s));
  }
  return sides;
}

VertexId other_end(const PrimalMesh& m, EdgeId e, VertexId v) {
  const auto [a, b] = m.edge(e);
  return a == v ? b : a;
}

// Whether the side's boundary turns at v: its end edges (v, a) and (v, b) are
// not on one straight line through v. EXACT: collinearity by orient2d on the
// three coordinate projections (dropping a coordinate is exact), then the
// directions by comparing coordinates.
bool boundary_turns(const PrimalMesh& m, VertexId v, EdgeId first, EdgeId last) {
  const Point3 &p = m.point(v), &a = m.point(other_end(m, first, v)), &b = m.point(other_end(m, last, v));
  if (orient2d(p.x, p.y, a.x, a.y, b.x, b.y) != Sign::Zero || orient2d(p.y, p.z, a.y, a.z, b.y, b.z) != Sign::Zero ||
      orient2d(p.z, p.x, a.z, a.x, b.z, b.x) != Sign::Zero)
    return true;
  for (int k = 0; k < 3; ++k)
    if (a[k] != p[k]) return (a[k] > p[k]) == (b[k] > p[k]);  // same direction: folded back
  return true;
}

Vec3 unit(Vec3 n) {
  const double l = norm(n);
  return l > 0 ? n / l : n;
}

}  // namespace

Vec3 surface_cell_normal(const PrimalMesh& m, PrimalCellId c) {
  const auto v = m.cell_vertices(c);
  if (v.size() == 3) return unit(cross(m.point(v[1]) - m.point(v[0]), m.point(v[2]) - m.point(v[0])));
  return unit(cross(m.point(v[2]) - m.point(v[0]), m.point(v[3]) - m.point(v[1])));
}

namespace {

// What a polygon is built from: the point ids of cells, curve edges and
// vertices (the latter made on first use), and the cells' normals.
struct DualPoints {
  const PrimalMesh& m;
  PolySurface& out;
  std::vector<std::uint32_t> cell_point, edge_point, vertex_point;
  std::vector<Vec3> normal;
  const std::vector<char>* whole;  // null: no vertex cut whole

  bool is_whole(VertexId v) const { return whole && (*whole)[v.idx] != 0; }

  std::uint32_t vertex(VertexId v) {
    if (vertex_point[v.idx] == UINT32_MAX)
      vertex_point[v.idx] = out.add_point(m.point(v), m.vertex_class(v), {SurfacePointOrigin::Kind::Vertex, v.idx});
    return vertex_point[v.idx];
  }
};

// A corner on the point of the previous one (cells sharing their centre)
// replaces it: the fan triangle between them has no area, the new corner's
// is the real one.
void add_corner(SurfacePolygonDraft& d, std::uint32_t p, Vec3 n, bool tested) {
  if (!d.points.empty() && d.points.back() == p) {
    d.fan_normal.back() = n;
    d.tested.back() = tested ? 1 : 0;
    return;
  }
  d.points.push_back(p);
  d.fan_normal.push_back(n);
  d.tested.push_back(tested ? 1 : 0);
}

SurfacePolygonDraft side_polygon(DualPoints& dp, VertexId v, const Side& s) {
  const PrimalMesh& m = dp.m;
  SurfacePolygonDraft d;
  d.reference = m.point(v);
  d.primal_vertex = m.input_vertex(v);
  d.surface = m.cell_class(s.cells.front()).tag;
  auto n_of = [&](PrimalCellId c) { return dp.normal[c.idx]; };
  const std::size_t k = s.cells.size();
  const auto pt = [&](PrimalCellId c) { return dp.cell_point[c.idx]; };
  // From cell a to the next cell b across their edge through v: one fan
  // triangle, or two through the edge's midpoint when its other end is cut
  // whole (that vertex's corners pass through it: design §15, the split).
  auto step = [&](PrimalCellId a, PrimalCellId b) {
    const EdgeId e = m.find_edge(v, corner_at(m, a, v).prev);
    if (!dp.is_whole(other_end(m, e, v))) return add_corner(d, pt(a), unit(n_of(a) + n_of(b)), true);
    add_corner(d, pt(a), n_of(a), true);
    add_corner(d, dp.edge_point[e.idx], n_of(b), true);
  };
  if (s.closed) {
    for (std::size_t i = 0; i < k; ++i) step(s.cells[i], s.cells[(i + 1) % k]);
    while (d.points.size() > 1 && d.points.back() == d.points.front()) {
      d.points.pop_back(), d.fan_normal.pop_back(), d.tested.pop_back();
    }
    return d;
  }
  const bool one_edge = s.first == s.last;
  const bool with_v = !one_edge && (m.vertex_class(v).dim == 0 || boundary_turns(m, v, s.first, s.last));
  if (with_v) add_corner(d, dp.vertex(v), n_of(s.cells.front()), false);
  add_corner(d, dp.edge_point[s.first.idx], n_of(s.cells.front()), true);
  for (std::size_t i = 0; i + 1 < k; ++i) step(s.cells[i], s.cells[i + 1]);
  add_corner(d, pt(s.cells.back()), n_of(s.cells.back()), true);
  // The last midpoint closes to v, or along the chord through v (straight
  // boundary: v lies on it, no area, not tested), or is the first one.
  if (!one_edge) add_corner(d, dp.edge_point[s.last.idx], n_of(s.cells.back()), false);
  return d;
}

// The polygon of cell c at a vertex v cut whole: its barycentric corner
// (v, the midpoint of the edge to the next vertex, c's vertex mean, the
// midpoint of the edge to the previous one), counterclockwise as c runs. It
// is the convex region of c nearer v than any other vertex of c in
// barycentric terms, so its two fan triangles about v turn counterclockwise
// whenever c is not degenerate; the two along its edges through v are not
// tested (they have no area).
SurfacePolygonDraft corner_polygon(DualPoints& dp, VertexId v, PrimalCellId c) {
  const PrimalMesh& m = dp.m;
  const Corner k = corner_at(m, c, v);
  SurfacePolygonDraft d;
  d.reference = m.point(v);
  d.primal_vertex = m.input_vertex(v);
  d.surface = m.cell_class(c).tag;
  const Vec3 n = dp.normal[c.idx];
  add_corner(d, dp.vertex(v), n, false);
  add_corner(d, dp.edge_point[m.find_edge(v, k.next).idx], n, true);
  add_corner(d, dp.cell_point[c.idx], n, true);
  add_corner(d, dp.edge_point[m.find_edge(v, k.prev).idx], n, false);
  return d;
}

// The cells' central points (a cell with a vertex cut whole: its vertex
// mean, as in 3D, design §14). Cells joined by an edge on no curve whose
// central points are equal (cocircular triangles: the two halves of a
// rectangle, a structured mesh) share one dual point, as the 3D cleanup
// collapses zero-length dual edges (paper §2.8): a dual edge of length zero
// would make its fan triangle flat. Equality of the rounded coordinates is an
// exact comparison; the points stay where the rule put them.
void add_cell_points(const PrimalMesh& m, DualPoints& dp) {
  std::vector<Point3> centre(m.num_cells());
  dp.normal.resize(m.num_cells());
  for (std::size_t c = 0; c < m.num_cells(); ++c) {
    const auto vs = m.cell_vertices(PrimalCellId(c));
    centre[c] = dp.whole && any_marked(vs, *dp.whole) ? vertex_mean(m, vs) : cell_central_point(m, PrimalCellId(c)).p;
    dp.normal[c] = surface_cell_normal(m, PrimalCellId(c));
  }
  UnionFind same(m.num_cells());
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    if (on_curve(m, EdgeId(e))) continue;
    const auto cs = m.edge_cells(EdgeId(e));
    if (centre[cs[0].idx] == centre[cs[1].idx]) same.unite(cs[0].idx, cs[1].idx);
  }
  dp.cell_point.assign(m.num_cells(), UINT32_MAX);
  for (std::size_t c = 0; c < m.num_cells(); ++c) {
    const std::uint32_t root = same.find(c);  // the smallest cell of its class: seen first
    if (dp.cell_point[root] == UINT32_MAX)
      dp.cell_point[root] = dp.out.add_point(centre[c], m.cell_class(PrimalCellId(c)),
                                             {SurfacePointOrigin::Kind::CellCentre, std::uint32_t(c)});
    dp.cell_point[c] = dp.cell_point[root];
  }
}

}  // namespace

PolySurface build_surface_dual(const PrimalMesh& m, const std::vector<char>* whole) {
  if (m.dim() != 2) throw std::logic_error("build_surface_dual needs a surface mesh (PrimalMesh::dim() == 2)");
  if (whole && whole->size() != m.num_vertices()) throw std::logic_error("build_surface_dual: one whole flag per vertex");
  PolySurface out;
  DualPoints dp{m, out, {}, std::vector<std::uint32_t>(m.num_edges(), UINT32_MAX),
                std::vector<std::uint32_t>(m.num_vertices(), UINT32_MAX), {}, whole};
  add_cell_points(m, dp);
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const auto [a, b] = m.edge(EdgeId(e));
    if (!on_curve(m, EdgeId(e)) && !dp.is_whole(a) && !dp.is_whole(b)) continue;
    dp.edge_point[e] = out.add_point(0.5 * (m.point(a) + m.point(b)), m.edge_class(EdgeId(e)),
                                     {SurfacePointOrigin::Kind::EdgeMidpoint, std::uint32_t(e)});
  }
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    if (dp.is_whole(VertexId(v))) {
      for (PrimalCellId c : m.vertex_cells(VertexId(v))) out.add_polygon(corner_polygon(dp, VertexId(v), c));
      continue;
    }
    for (const Side& s : vertex_sides(m, VertexId(v))) {
      const SurfacePolygonDraft d = side_polygon(dp, VertexId(v), s);
      if (d.points.size() < 3)
        throw InputError(m.source(), cell_name(m, s.cells.front()),
                         "the cells around vertex " + std::to_string(m.input_vertex(VertexId(v)) + 1) +
                             " make no polygon (" + std::to_string(s.cells.size()) + " cell(s) in a closed fan)");
      out.add_polygon(d);
    }
  }
  return out;
}

}  // namespace polydual
