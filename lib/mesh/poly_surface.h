// The dual of a surface mesh (design §15): a mesh of polygons, one per side
// of each primal vertex, on the surfaces of a network (fracture networks,
// closed surfaces). What the paper's Algorithm 1 gives "with trivial
// modifications" for combinations of surfaces alone.
//
// Each dual point carries its model classification and its primal origin (a
// cell's central point, a curve edge's midpoint or a primal vertex); each
// polygon its primal vertex (input numbering), its surface tag, its reference
// point (the primal vertex, an input point: exact) and, per corner i, the
// direction that orients the fan triangle (reference, p_i, p_{i+1}) on the
// surface (a primal cell normal, floating point). Polygons are counterclockwise
// about that direction.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/classification.h"
#include "core/vec3.h"

namespace polydual {

struct SurfacePointOrigin {
  enum class Kind : std::uint8_t { CellCentre = 0, EdgeMidpoint = 1, Vertex = 2 };
  Kind kind = Kind::CellCentre;
  std::uint32_t id = 0;  // the primal cell, edge or vertex (PrimalMesh ids)
};

// One polygon as the builder hands it over: its corners (point ids) and, per
// corner i, the orientation of the fan triangle (reference, p_i, p_{i+1}),
// `tested` 0 when that triangle lies along the side's boundary through the
// reference point (an edge at the reference, or the chord through it where a
// straight boundary curve passes): it has no area and is not tested.
struct SurfacePolygonDraft {
  std::vector<std::uint32_t> points;
  std::vector<Vec3> fan_normal;
  std::vector<std::uint8_t> tested;
  Point3 reference;
  std::uint64_t primal_vertex = 0;
  std::int32_t surface = 0;
};

class PolySurface {
 public:
  std::size_t num_points() const { return points_.size(); }
  std::size_t num_polygons() const { return surface_.size(); }
  std::size_t num_corners() const { return corner_point_.size(); }

  const Point3& point(std::size_t p) const { return points_[p]; }
  const std::vector<Point3>& points() const { return points_; }
  ModelRef point_class(std::size_t p) const { return point_class_[p]; }
  SurfacePointOrigin point_origin(std::size_t p) const { return point_origin_[p]; }

  std::span<const std::uint32_t> polygon(std::size_t i) const {
    return {corner_point_.data() + offset_[i], corner_point_.data() + offset_[i + 1]};
  }
  std::span<const Vec3> fan_normals(std::size_t i) const {
    return {fan_normal_.data() + offset_[i], fan_normal_.data() + offset_[i + 1]};
  }
  std::span<const std::uint8_t> fan_tested(std::size_t i) const {
    return {fan_tested_.data() + offset_[i], fan_tested_.data() + offset_[i + 1]};
  }
  const Point3& reference(std::size_t i) const { return reference_[i]; }
  std::uint64_t primal_vertex(std::size_t i) const { return primal_vertex_[i]; }
  std::int32_t surface(std::size_t i) const { return surface_[i]; }

  std::uint32_t add_point(const Point3& p, ModelRef cls, SurfacePointOrigin origin);
  void add_polygon(const SurfacePolygonDraft& d);
  // Moves a point (smoothing); its class and origin stay.
  void set_point(std::size_t p, const Point3& x) { points_[p] = x; }

 private:
  std::vector<Point3> points_;
  std::vector<ModelRef> point_class_;
  std::vector<SurfacePointOrigin> point_origin_;
  std::vector<std::uint64_t> offset_{0};
  std::vector<std::uint32_t> corner_point_;
  std::vector<Vec3> fan_normal_;
  std::vector<std::uint8_t> fan_tested_;
  std::vector<Point3> reference_;
  std::vector<std::uint64_t> primal_vertex_;
  std::vector<std::int32_t> surface_;
};

}  // namespace polydual
