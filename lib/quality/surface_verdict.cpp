// The surface dual's exact validity and its area identity.
#include "quality/surface_verdict.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "predicates/predicates.h"

namespace polydual {

bool surface_polygon_valid(const PolySurface& s, std::size_t i) {
  const auto pts = s.polygon(i);
  const auto n = s.fan_normals(i);
  const auto tested = s.fan_tested(i);
  const Point3& r = s.reference(i);
  for (std::size_t k = 0; k < pts.size(); ++k) {
    if (!tested[k]) continue;
    if (surface_turn(r, s.point(pts[k]), s.point(pts[(k + 1) % pts.size()]), n[k]) != Sign::Positive) return false;
  }
  return true;
}

SurfaceVerdicts surface_verdicts(const PolySurface& s) {
  SurfaceVerdicts v;
  v.valid.assign(s.num_polygons(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.num_polygons(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) v.valid[i] = surface_polygon_valid(s, i) ? 1 : 0;
  });
  for (std::size_t i = 0; i < s.num_polygons(); ++i) {
    v.invalid += v.valid[i] == 0;
    for (std::uint8_t t : s.fan_tested(i)) v.fan_triangles += t;
  }
  return v;
}

double surface_polygon_area(const PolySurface& s, std::size_t i) {
  const auto pts = s.polygon(i);
  const auto n = s.fan_normals(i);
  const Point3& r = s.reference(i);
  long double a = 0;
  for (std::size_t k = 0; k < pts.size(); ++k)
    a += dot(n[k], cross(s.point(pts[k]) - r, s.point(pts[(k + 1) % pts.size()]) - r));
  return double(a / 2);
}

namespace {

double cell_area(const PrimalMesh& m, PrimalCellId c) {
  const auto v = m.cell_vertices(c);
  if (v.size() == 3) return 0.5 * norm(cross(m.point(v[1]) - m.point(v[0]), m.point(v[2]) - m.point(v[0])));
  return 0.5 * norm(cross(m.point(v[2]) - m.point(v[0]), m.point(v[3]) - m.point(v[1])));
}

// EXACT: whether every vertex of the surface's cells lies in the plane of
// three non-collinear ones (the first cell's first corner that is not).
bool surface_planar(const PrimalMesh& m, const std::vector<PrimalCellId>& cells) {
  std::array<Point3, 3> base{};
  bool have_base = false;
  for (PrimalCellId c : cells) {
    const auto v = m.cell_vertices(c);
    for (std::size_t k = 0; k < v.size() && !have_base; ++k) {
      const Point3 &a = m.point(v[k]), &b = m.point(v[(k + 1) % v.size()]), &d = m.point(v[(k + 2) % v.size()]);
      if (orient2d(a.x, a.y, b.x, b.y, d.x, d.y) != Sign::Zero || orient2d(a.y, a.z, b.y, b.z, d.y, d.z) != Sign::Zero ||
          orient2d(a.z, a.x, b.z, b.x, d.z, d.x) != Sign::Zero)
        base = {a, b, d}, have_base = true;
    }
    if (!have_base) continue;
    for (VertexId x : v)
      if (orient3d(base[0], base[1], base[2], m.point(x)) != Sign::Zero) return false;
  }
  return have_base;
}

}  // namespace

SurfaceAreaIdentity surface_area_identity(const PrimalMesh& m, const PolySurface& s) {
  SurfaceAreaIdentity out;
  std::map<std::int32_t, std::vector<PrimalCellId>> cells;
  std::map<std::int32_t, long double> primal, dual;
  for (std::size_t c = 0; c < m.num_cells(); ++c) {
    const std::int32_t tag = m.cell_class(PrimalCellId(c)).tag;
    cells[tag].push_back(PrimalCellId(c));
    primal[tag] += cell_area(m, PrimalCellId(c));
  }
  for (std::size_t i = 0; i < s.num_polygons(); ++i) dual[s.surface(i)] += surface_polygon_area(s, i);
  for (const auto& [tag, cs] : cells) {
    SurfaceArea& a = out.surfaces[tag];
    a.primal = double(primal[tag]);
    a.dual = double(dual[tag]);
    a.planar = surface_planar(m, cs);
    const double rel = a.primal > 0 ? std::abs(a.dual - a.primal) / a.primal : 0.0;
    out.max_rel_error_all = std::max(out.max_rel_error_all, rel);
    if (!a.planar) continue;
    ++out.planar;
    out.max_rel_error = std::max(out.max_rel_error, rel);
  }
  return out;
}

}  // namespace polydual
