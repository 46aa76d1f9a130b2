// Smoothing of a surface dual within its surfaces (design §15; the 2D
// counterpart of paper §3.3's smoothing, without the Newton solve): each
// cell's central point moves towards the mean of its neighbours in the
// polygons that use it (a Laplacian step, then half of it), projected on its
// primal cell's plane, and the move is kept only if every polygon using the
// point stays valid by the EXACT fan test (quality/surface_verdict.h) and the
// smallest fan-triangle quality among them increases (floating point). Edge
// midpoints and primal vertices stay: they carry the curves and corners.
// Serial sweeps in point order: the same result for any thread count.
#pragma once
#include <cstddef>

#include "mesh/poly_surface.h"
#include "mesh/primal_mesh.h"

namespace polydual {

struct SurfaceSmoothParams {
  int sweeps = 4;  // passes over the movable points; 0: no smoothing
};

struct SurfaceSmoothReport {
  int sweeps = 0;
  std::size_t moved = 0;          // accepted moves, all sweeps
  double min_quality_before = 0;  // smallest fan-triangle quality over all polygons
  double min_quality_after = 0;
};

// A fan triangle's quality, 4 sqrt(3) A / (sum of its squared edge lengths):
// 1 for an equilateral triangle, <= 0 when it turns clockwise (A signed about
// its direction). A polygon's quality is the smallest over its tested fan
// triangles. Floating point.
double surface_polygon_quality(const PolySurface& s, std::size_t polygon);

// `m` is the primal `s` was built from (its cells' planes).
SurfaceSmoothReport smooth_surface(PolySurface& s, const PrimalMesh& m, const SurfaceSmoothParams& params = {});

}  // namespace polydual
