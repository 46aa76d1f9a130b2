// Central points of tets and triangles (design §4 steps 1-2, paper §2.4).
#pragma once
#include <array>

#include "core/vec3.h"

namespace polydual {

struct CentralPoint {
  Point3 p;
  bool well_centred = false;  // EXACT: the closed simplex contains its circumcenter
  // For a well-centred tet: a bound on max_k |p_k - exact circumcentre_k|
  // (proofs/star_filter.md, L9c), or +infinity; unused otherwise.
  double error = 0;
};

// The circumcenter if the closed tet contains it (decided exactly), otherwise
// the point where the segment centroid -> circumcenter leaves the tet, less a
// relative 2^-20 of the segment (strictly inside, well beyond rounding). The
// clamped point is verified to lie in the closed tet with exact orientation
// tests (pulled towards the centroid until it does). The circumcenter's
// coordinates themselves are rounded doubles.
CentralPoint tet_central_point(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

// Same rule in the triangle's plane. Coordinates are computed as a + s(b-a) +
// t(c-a), so a triangle lying in an axis-aligned plane gives points exactly in
// that plane.
CentralPoint triangle_central_point(const Point3& a, const Point3& b, const Point3& c);

// The centre of a model-face triangle when the dual keeps the primal's
// boundary (BoundaryMode::Keep): the circumcentre if it lies strictly inside
// the triangle (EXACT: every barycentric sign positive), else the centroid, so
// the three quads (vertex, midpoint, centre, midpoint) tiling the triangle are
// never degenerate (a right triangle's circumcentre is its hypotenuse's
// midpoint). well_centred: strictly inside. Computed as a + s(b-a) + t(c-a),
// as triangle_central_point.
CentralPoint triangle_inner_point(const Point3& a, const Point3& b, const Point3& c);

// The centre of a model-face triangle under the paper's caps: the rule of
// triangle_central_point, unless that point lies on an edge of the triangle
// that is on a model edge (on_model_edge[k]: the edge opposite vertex k),
// which happens when the angle at k is right or obtuse (EXACT: the sign of the
// circumcentre's barycentric coordinate at k; an obtuse triangle's clamped
// point lands on its longest edge): then the centroid. The caps join the
// centres of the triangles round a vertex on a model edge with the edge's
// midpoint; a centre on the model edge made the cap face between them flat
// (all four points on the edge's line: a corner of kappa/3 9e13 on a CGAL
// Mesh_3 mesh once the tet optimisation had moved its boundary vertices).
CentralPoint cap_triangle_point(const Point3& a, const Point3& b, const Point3& c, const bool on_model_edge[3]);

}  // namespace polydual
