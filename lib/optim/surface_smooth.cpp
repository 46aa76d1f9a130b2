// smooth_surface: Laplacian steps on the cells' planes, kept when valid and better.
#include "optim/surface_smooth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "quality/surface_verdict.h"

namespace polydual {

namespace {

// Fan triangle k of polygon i: its quality (see the header).
double fan_quality(const PolySurface& s, std::size_t i, std::size_t k) {
  const auto pts = s.polygon(i);
  const Point3 &r = s.reference(i), &a = s.point(pts[k]), &b = s.point(pts[(k + 1) % pts.size()]);
  const double area = 0.5 * dot(s.fan_normals(i)[k], cross(a - r, b - r));
  const double l2 = norm2(a - r) + norm2(b - r) + norm2(b - a);
  return l2 > 0 ? 4 * std::sqrt(3.0) * area / l2 : 0.0;
}

}  // namespace

double surface_polygon_quality(const PolySurface& s, std::size_t i) {
  double q = std::numeric_limits<double>::infinity();
  const auto tested = s.fan_tested(i);
  for (std::size_t k = 0; k < tested.size(); ++k)
    if (tested[k]) q = std::min(q, fan_quality(s, i, k));
  return q;
}

namespace {

// Per point: the polygons using it and its neighbours along them.
struct PointStar {
  std::vector<std::vector<std::uint32_t>> polygons, neighbours;
};
PointStar point_stars(const PolySurface& s) {
  PointStar st;
  st.polygons.resize(s.num_points());
  st.neighbours.resize(s.num_points());
  for (std::size_t i = 0; i < s.num_polygons(); ++i) {
    const auto p = s.polygon(i);
    for (std::size_t k = 0; k < p.size(); ++k) {
      st.polygons[p[k]].push_back(std::uint32_t(i));
      st.neighbours[p[k]].push_back(p[(k + 1) % p.size()]);
      st.neighbours[p[k]].push_back(p[(k + p.size() - 1) % p.size()]);
    }
  }
  return st;
}

// What a move is judged by: the polygons at the point that the EXACT fan
// test finds invalid, then the smallest quality of the tested fan triangles
// at the point (floating point). A move is kept when it lowers the first, or
// keeps it and raises the second: it never makes a valid polygon invalid.
struct Score {
  std::size_t invalid = 0;
  double quality = std::numeric_limits<double>::infinity();
  bool better_than(const Score& o) const { return invalid < o.invalid || (invalid == o.invalid && quality > o.quality); }
};
Score score(const PolySurface& s, const std::vector<std::uint32_t>& polygons, std::uint32_t p) {
  Score sc;
  for (std::uint32_t i : polygons) {
    sc.invalid += !surface_polygon_valid(s, i);
    const auto pts = s.polygon(i);
    const auto tested = s.fan_tested(i);
    for (std::size_t k = 0; k < pts.size(); ++k)
      if (tested[k] && (pts[k] == p || pts[(k + 1) % pts.size()] == p))
        sc.quality = std::min(sc.quality, fan_quality(s, i, k));
  }
  return sc;
}

// x projected on the plane of primal cell c (its first vertex, its corners'
// normal for a triangle, the diagonals' for a quadrangle). Floating point.
Point3 on_cell_plane(const PrimalMesh& m, PrimalCellId c, const Point3& x) {
  const auto v = m.cell_vertices(c);
  const Vec3 n = v.size() == 3 ? cross(m.point(v[1]) - m.point(v[0]), m.point(v[2]) - m.point(v[0]))
                               : cross(m.point(v[2]) - m.point(v[0]), m.point(v[3]) - m.point(v[1]));
  const double nn = norm2(n);
  if (nn == 0) return x;
  Point3 o = m.point(v[0]);
  if (v.size() == 4) o = 0.25 * (m.point(v[0]) + m.point(v[1]) + m.point(v[2]) + m.point(v[3]));
  return x - (dot(x - o, n) / nn) * n;
}

// One point: the Laplacian target, then half the step; returns whether it moved.
bool smooth_point(PolySurface& s, const PrimalMesh& m, const PointStar& st, std::uint32_t p) {
  const auto& nb = st.neighbours[p];
  if (nb.empty()) return false;
  Point3 mean{0, 0, 0};
  for (std::uint32_t q : nb) mean += s.point(q);
  mean = mean / double(nb.size());
  const Point3 old = s.point(p);
  const Score before = score(s, st.polygons[p], p);
  for (double step : {1.0, 0.5}) {
    const Point3 x = on_cell_plane(m, PrimalCellId(std::size_t(s.point_origin(p).id)), old + step * (mean - old));
    if (!is_finite(x) || x == old) continue;
    s.set_point(p, x);
    if (score(s, st.polygons[p], p).better_than(before)) return true;
    s.set_point(p, old);
  }
  return false;
}

double min_quality(const PolySurface& s) {
  double q = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s.num_polygons(); ++i) q = std::min(q, surface_polygon_quality(s, i));
  return s.num_polygons() ? q : 0.0;
}

}  // namespace

SurfaceSmoothReport smooth_surface(PolySurface& s, const PrimalMesh& m, const SurfaceSmoothParams& params) {
  SurfaceSmoothReport r;
  r.min_quality_before = min_quality(s);
  const PointStar st = point_stars(s);
  for (int sweep = 0; sweep < params.sweeps; ++sweep) {
    ++r.sweeps;
    std::size_t moved = 0;
    for (std::uint32_t p = 0; p < s.num_points(); ++p)
      if (s.point_origin(p).kind == SurfacePointOrigin::Kind::CellCentre) moved += smooth_point(s, m, st, p);
    r.moved += moved;
    if (moved == 0) break;
  }
  r.min_quality_after = min_quality(s);
  return r;
}

}  // namespace polydual
