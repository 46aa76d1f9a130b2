// Boundary constraints of the optimisers (paper 3.3: "movement of mesh vertices
// on the boundary was constrained to the original facetization by use of a
// dynamically changing local parametric space"; design §7).
//
// The facetisation is the primal's triangles classified on model faces
// (ModelRef{2,T}) and edges classified on model edges ({1,T}): ModelFacets
// (mesh/model_facets.h), built once from the primal. A dual point
// classified {2,T} lives on one triangle of model face T, its "current" triangle;
// a point {1,T} on one segment of model edge T; {0,*} points are fixed.
//
// Local parametric space (concrete definition): the plane of the current
// triangle with an orthonormal basis (t1, t2), origin at the point (or the line of
// the current segment, basis t1). An optimiser moves the point to x = o + B u;
// project() then walks from the current primitive to the nearest point of the
// model entity: it examines the primitives of the same model entity that share a
// primal vertex with the current one, moves to the one holding the nearest point,
// and repeats until the current one is the nearest (at most kMaxHops hops). The result
// lies on a primitive, so it is on the original facetisation up to rounding, and
// commit() makes that primitive current (re-centring the parametric space).
//
// Own-primitive constraints (keep = true, for a dual built with
// BoundaryMode::Keep, build_dual.h): each boundary point stays on the primal
// simplex it was made on, so the dual's boundary stays the primal's boundary
// triangulation (proofs/dual_invariants.md L5). By the point's PointOrigin:
// a model-face triangle's centre moves in that triangle only, an edge's
// midpoint on that edge only (a model edge's or a model face's), a primal
// vertex's point is fixed, and so is a point without a PointOrigin (a dual
// read from a file). project() is then the closest point of that one
// primitive (no walk).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/model_facets.h"
#include "mesh/poly_mesh.h"

namespace polydual {

class BoundaryConstraints {
 public:
  static constexpr std::uint32_t kNone = UINT32_MAX;

  // Finds each boundary point's nearest primitive of its model entity (uniform
  // grid search). A point whose model entity has no primitive in `facets` is
  // fixed (dof 0). Lazy: the search for a point runs at its first ensure()
  // instead, from its position then (the same primitive as the eager search
  // while the point has not moved: an optimiser that moves only the points
  // it visits, and ensures each before its first move, sees the same
  // constraints; --optimize untangle visits a few hundred of ~60k boundary
  // points at 100k tets). `mesh` must outlive a lazy instance.
  BoundaryConstraints(const ModelFacets& facets, const PolyMesh& mesh, bool lazy = false, bool keep = false);
  // Lazy: finds p's initial primitive if not yet done (from p's current
  // position). Concurrent calls for different points are safe.
  void ensure(PointId p) {
    if (lazy_ && current_[p.idx] == kNone && (dof_[p.idx] == 1 || dof_[p.idx] == 2)) assign_initial(p.idx);
  }

  // Degrees of freedom of point p: 0 fixed, 1 on a model edge, 2 on a model face,
  // 3 interior (free).
  int dof(PointId p) const { return dof_[p.idx]; }
  std::uint32_t current(PointId p) const { return current_[p.idx]; }
  // Orthonormal tangent basis of p's current primitive (dof(p) vectors).
  void tangent_basis(PointId p, Vec3 basis[3]) const;
  // Nearest point of p's model entity to x, walking from primitive `start`
  // (kNone: p's current); writes the primitive reached. Interior points: x.
  Point3 project(PointId p, const Point3& x, std::uint32_t* prim, std::uint32_t start = kNone) const;
  void commit(PointId p, std::uint32_t prim) { if (dof_[p.idx] == 1 || dof_[p.idx] == 2) current_[p.idx] = prim; }
  // Distance from x to p's model entity (exhaustive; for tests and checks).
  double distance_to_entity(PointId p, const Point3& x) const;
  std::size_t num_primitives() const { return prims_.size(); }
  // Whether points keep their own primitive (the constructor's `keep`).
  bool own_primitives() const { return keep_; }

 private:
  struct Prim {
    std::array<VertexId, 3> v;  // v[2] unused for segments
    std::int8_t dim;            // 2 triangle, 1 segment
    std::int32_t tag;
    std::uint32_t src;          // its TriId (dim 2) or EdgeId (dim 1) in the primal
  };
  // The walk of project() stops after this many moves (the nearest point is
  // then a local one; on a facetisation of a smooth entity a few suffice).
  static constexpr int kMaxHops = 64;
  // Grid cells are this many mean primitive extents wide (a primitive then
  // meets a few cells), at least kMinGridCell (degenerate facetisations), and
  // at most kMaxGridCells along the longest axis (memory).
  static constexpr double kGridCellExtents = 2.0;
  static constexpr double kMinGridCell = 1e-300;
  static constexpr double kMaxGridCells = 256.0;
  static constexpr double kFar = 1e300;  // the bounding box's start (beyond any coordinate)

  // The constructor's phases, in order.
  void collect_primitives(const ModelFacets& facets);
  void index_vertex_primitives();
  void build_grid();
  void assign_initial_primitives();
  void assign_initial(std::size_t p);  // p's nearest primitive (dof_[p] already set)
  Point3 closest(std::uint32_t prim, const Point3& x) const;
  // seed (kNone: none): a primitive of the entity tried first; the result is
  // the same with or without it (it only lets the box test skip more).
  std::uint32_t nearest_by_grid(const Point3& x, int dim, std::int32_t tag, std::uint32_t seed = kNone) const;
  // The primitive the dual point was made on (its PointOrigin: that triangle,
  // that edge, or a primitive at that vertex) if it belongs to the point's
  // entity, else kNone.
  std::uint32_t origin_primitive(const PointOrigin& o, const ModelRef& r) const;
  // keep_: the primitive of p's own triangle or edge (its PointOrigin), or
  // kNone (a vertex's point, or a point whose origin has no primitive).
  std::uint32_t own_primitive(std::size_t p) const;
  // keep_: adds a segment primitive for every edge on a model face (tag
  // kFaceEdgeTag: no model edge's walk enters it; keep_ walks nowhere).
  void collect_face_edges(const ModelFacets& facets);
  static constexpr std::int32_t kFaceEdgeTag = INT32_MIN;

  std::vector<Point3> verts_;
  std::vector<Prim> prims_;                       // triangles by TriId, then segments by EdgeId
  std::uint32_t num_tri_prims_ = 0;
  std::vector<std::array<Point3, 2>> box_;        // per primitive: bounding box (lo, hi)
  double box_slack_ = 0;                          // the box test's margin for rounding (scale x 1e-10)
  std::vector<std::uint32_t> vprim_off_, vprim_;  // primal vertex -> primitives
  std::vector<ModelRef> cls_;                     // per dual point
  std::vector<std::uint8_t> dof_;
  std::vector<std::uint32_t> current_;
  const PolyMesh* mesh_ = nullptr;  // positions and origins of the points
  bool lazy_ = false;
  bool keep_ = false;
  // Uniform grid over primitive bounding boxes (initial assignment only).
  Point3 lo_;
  double h_ = 1;
  std::array<int, 3> n_{1, 1, 1};
  std::vector<std::uint32_t> grid_off_, grid_;
};

// Closest point of triangle (a,b,c) to x (Ericson, Real-Time Collision Detection 5.1.5).
Point3 closest_point_on_triangle(const Point3& x, const Point3& a, const Point3& b, const Point3& c);
Point3 closest_point_on_segment(const Point3& x, const Point3& a, const Point3& b);

}  // namespace polydual
