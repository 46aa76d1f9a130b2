// Refusal of tet meshes that cover a place twice or hold a crack (design §3,
// proofs/self_overlap.md L15): run by classify() on the mesh whose topology it
// has just built, after the checks that every tet is positively oriented
// (exact) and that every triangle has at most two tets, on its two sides.
// Those local checks pass two copies of a mesh at one place, two copies
// overlapping by half, a copy nested inside another, and a crack made by a
// duplicated vertex; this check refuses them:
//   1. coincident vertices: two vertices at exactly the same position (a
//      radix sort on a hash of the coordinates, then a sort on the exact
//      coordinates inside each run of one hash). A fracture or sheet is never
//      encoded so: it is a model face whose triangles are shared by the tets
//      on both sides;
//   2. the boundary (the triangles with one tet) is embedded: two boundary
//      triangles meet only in the vertices and edge they share (exact tests,
//      classify/triangle_crossing.h, on every pair whose boxes meet: pairs
//      sharing an edge or a vertex from the mesh, the others from a grid or
//      CGAL's box intersection);
//   3. no part lies inside another: for one boundary triangle of each piece
//      of the boundary (pieces joined across edges with exactly two boundary
//      triangles), no tet but its own holds its centroid (exact).
// The combinatorial closure of the boundary (every edge of a boundary
// triangle has an even number of them) needs no test: it follows from the
// local checks (L15, step 0).
// Every decision is exact (lib/predicates); the hashes, grids and boxes that
// pick the candidates are built from the input doubles by monotone maps, so
// they never leave a candidate out. Cost: a pass over the tets' faces, then
// work in the boundary triangles (plus a pass over the tets when the
// boundary has more than one piece); a vertex or edge with k boundary
// triangles costs k^2 pair tests.
#pragma once
#include <cstddef>

#include "mesh/classified_tet_mesh.h"

namespace polydual {

// What the check looked at and its wall-clock seconds (for tests and
// benchmarks; classify() keeps the total in ClassifyStats::seconds_overlap).
struct SelfOverlapStats {
  std::size_t boundary_triangles = 0;  // triangles with one tet
  std::size_t tested_pairs = 0;        // boundary triangle pairs tested exactly
  std::size_t pieces = 0;              // pieces of the boundary (one centroid tested each)
  double seconds_vertices = 0, seconds_boundary = 0, seconds_nesting = 0;
};

// Throws InputError naming m.source(), the place ("vertex N" or "tet N", the
// file's 1-based numbering) and the reason: the two coincident vertices and
// the tets using them; the two boundary triangles (their vertices) and their
// tets that meet away from what they share; or the tet that holds the
// centroid of another tet's boundary triangle.
void check_self_overlap(const ClassifiedTetMesh& m, SelfOverlapStats* stats = nullptr);

}  // namespace polydual
