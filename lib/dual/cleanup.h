// Cleanup of the raw dual (SPEC §4 step 9, paper §2.8): merge points known to
// coincide exactly, collapse short edges between points of the same
// classification, rewrite face loops, drop faces that degenerate below three
// points, and drop points no face uses. Works on a PolyMesh whose cells are not
// assembled yet (faces with owner/neighbour only).
#pragma once
#include <utility>
#include <vector>

#include "core/handles.h"
#include "mesh/poly_mesh.h"

namespace polydual {

struct CleanupResult {
  std::size_t merged_points = 0, collapsed_points = 0, dropped_faces = 0;
};

// exact_pairs: pairs of points that coincide exactly (decided by the caller
// with exact predicates). collapse_length: absolute length below which an edge
// between two points of equal classification is collapsed (0: none). Short
// edges are looked for in short_pairs (pairs of points the caller found closer
// than collapse_length: the dual's tet-centre edges, found from the primal
// triangles they cross) and in the loops of scan_faces (sorted face ids:
// every face with an edge that short_pairs does not cover).
CleanupResult cleanup_dual(PolyMesh& mesh, const std::vector<std::pair<PointId, PointId>>& exact_pairs,
                           const std::vector<std::pair<PointId, PointId>>& short_pairs, double collapse_length,
                           const std::vector<std::uint32_t>& scan_faces);

}  // namespace polydual
