#include "mesh/poly_surface.h"

#include <stdexcept>

namespace polydual {

std::uint32_t PolySurface::add_point(const Point3& p, ModelRef cls, SurfacePointOrigin origin) {
  points_.push_back(p);
  point_class_.push_back(cls);
  point_origin_.push_back(origin);
  return std::uint32_t(points_.size() - 1);
}

void PolySurface::add_polygon(const SurfacePolygonDraft& d) {
  if (d.points.size() < 3 || d.fan_normal.size() != d.points.size() || d.tested.size() != d.points.size())
    throw std::logic_error("PolySurface::add_polygon: a polygon needs 3+ corners and one fan normal per corner");
  corner_point_.insert(corner_point_.end(), d.points.begin(), d.points.end());
  fan_normal_.insert(fan_normal_.end(), d.fan_normal.begin(), d.fan_normal.end());
  fan_tested_.insert(fan_tested_.end(), d.tested.begin(), d.tested.end());
  offset_.push_back(corner_point_.size());
  reference_.push_back(d.reference);
  primal_vertex_.push_back(d.primal_vertex);
  surface_.push_back(d.surface);
}

}  // namespace polydual
