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
// between two points of equal classification is collapsed (0: none). Edges of
// the face loops between two points with ids below `scan_from` are not looked
// for in the loops: the caller lists in short_pairs every such edge that is
// shorter than collapse_length (the dual's tet-centre edges, found from the
// primal triangles they cross); edges with an end at or above scan_from are
// found face by face. Pass scan_from = 0 to test every loop edge.
CleanupResult cleanup_dual(PolyMesh& mesh, const std::vector<std::pair<PointId, PointId>>& exact_pairs,
                           const std::vector<std::pair<PointId, PointId>>& short_pairs, double collapse_length,
                           std::uint32_t scan_from);

}  // namespace polydual
