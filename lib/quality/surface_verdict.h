// Validity and the area identity of a surface dual (design §15).
//
// Validity, the 2D analogue of the star test (paper §3.1): a polygon is valid
// iff every tested fan triangle (r, p_i, p_{i+1}), r its reference point (the
// primal vertex, an input point), turns counterclockwise about the fan
// triangle's direction n_i (predicates.h: surface_turn, the sign of
// n_i . ((p_i - r) x (p_{i+1} - r))). EXACT given the points (rounded
// constructions) and the directions n_i, which are floating point: a primal
// cell's unit normal, or the normalised sum of the two cells' normals for a
// fan triangle across an edge (on a curved surface the orientation of a
// triangle spanning two cells is defined by both). On a planar surface every
// n_i is the plane's normal, so the test is orient2d in the plane; in an axis
// plane (z = const) exactly so, n_i being (0, 0, +-1) exactly.
//
// The area identity: on a planar surface the polygons tile the primal, so
// the sum of their signed areas (fan triangles about the reference point,
// signed by n_i) equals the primal's area. Areas are FLOATING POINT (long
// double sums); the identity is reported as the relative error per planar
// surface. Planarity of a surface is decided EXACTLY (orient3d of every
// vertex against three non-collinear vertices of the surface).
#pragma once
#include <cstdint>
#include <map>
#include <vector>

#include "mesh/poly_surface.h"
#include "mesh/primal_mesh.h"

namespace polydual {

struct SurfaceVerdicts {
  std::vector<std::uint8_t> valid;  // per polygon: 1 valid, 0 not
  std::size_t invalid = 0;
  std::size_t fan_triangles = 0;    // tested
};

// EXACT (see above); parallel over polygons, the same result for any thread count.
SurfaceVerdicts surface_verdicts(const PolySurface& s);
bool surface_polygon_valid(const PolySurface& s, std::size_t polygon);

// A polygon's signed area: sum over its fan triangles of
// n_i . ((p_i - r) x (p_{i+1} - r)) / 2. Floating point.
double surface_polygon_area(const PolySurface& s, std::size_t polygon);

struct SurfaceArea {
  double primal = 0, dual = 0;
  bool planar = false;  // EXACT
};
struct SurfaceAreaIdentity {
  std::map<std::int32_t, SurfaceArea> surfaces;  // by surface tag
  std::size_t planar = 0;       // planar surfaces
  double max_rel_error = 0;     // max |dual - primal| / primal over planar surfaces
  // The same over all surfaces: not an identity on a curved surface (the fan
  // triangles across an edge leave its cells' planes), a measure of it.
  double max_rel_error_all = 0;
};
SurfaceAreaIdentity surface_area_identity(const PrimalMesh& m, const PolySurface& s);

}  // namespace polydual
