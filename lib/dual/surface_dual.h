// The dual of a surface mesh or surface network (design §15; paper §1: the
// algorithm applies "with trivial modifications" to combinations of surfaces
// alone, such as a fracture network). Algorithm 1 in two dimensions:
//  - the sides of a primal vertex v are the cells around it joined through
//    edges on no model curve (an edge of 3+ cells, where fractures cross, is
//    always on one: build_primal classifies it so); each side is a fan,
//    closed (v inside a surface) or open between two curve edges;
//  - one polygon per side: the central points of its cells (circumcentre of
//    a triangle where it holds it, else clamped; quadrangle: vertex mean;
//    dual/primal_central_points.h), the midpoints of its two end edges on
//    model curves, and v itself where v is a model vertex or where the side's
//    boundary turns (the end edges are not collinear through v: the 2D
//    analogue of the caps at model vertices). Where both ends of an open fan
//    are the same edge (a curve ending inside a surface) the polygon takes its
//    midpoint once and not v: it closes around v.
// Conformal by construction: the point of a cell, a curve edge or a vertex is
// one point shared by every polygon that uses it, so neighbouring polygons
// share each dual edge, and polygons on both sides of a crossing line share
// its midpoints and points.
// Cells joined by an edge on no curve whose central points are equal
// (cocircular triangles) share one dual point: no dual edge of length zero.
// Deterministic numbering: points are the cells' central points (cell order),
// then the midpoints of curve edges (edge order), then the primal vertices
// used (vertex order); polygons in vertex order, a vertex's sides in order of
// their smallest cell.
#pragma once
#include <vector>

#include "mesh/poly_surface.h"
#include "mesh/primal_mesh.h"

namespace polydual {

// Whole cuts (the split, design §15): a vertex v marked in `whole` (one flag
// per vertex of m; null: none) has one polygon per cell around it, the
// cell's barycentric corner (v, the midpoints of the cell's two edges
// through v, the cell's vertex mean): convex, so valid by the exact fan test
// whenever the cell is not degenerate. Every cell with a vertex cut whole
// takes its vertex mean as central point and every edge through one has its
// midpoint as a dual point, which the polygons of the edge's other vertex
// pass through between the edge's two cells: any set of whole vertices
// leaves the dual conformal, and the polygons still tile planar surfaces.
//
// m.dim() must be 2. Throws InputError naming the source and the cells when
// two cells of one surface run their common edge the same way (the surface's
// orientation is inconsistent there) or when a side is too small to make a
// polygon.
PolySurface build_surface_dual(const PrimalMesh& m, const std::vector<char>* whole = nullptr);

// A primal cell's unit normal, floating point: the cross product of a
// triangle's edges, or of a quadrangle's diagonals (its mean plane's normal).
Vec3 surface_cell_normal(const PrimalMesh& m, PrimalCellId c);

}  // namespace polydual
