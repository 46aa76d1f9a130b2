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

}  // namespace polydual
