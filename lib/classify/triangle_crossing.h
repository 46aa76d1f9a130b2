// Whether two triangles of a mesh meet away from what they share: the exact
// test behind the embedded-boundary step of the self-overlap check
// (classify/self_overlap.h; proofs/self_overlap.md L15, step 2).
#pragma once
#include <array>
#include <vector>

#include "core/handles.h"
#include "core/vec3.h"

namespace polydual {

// EXACT. f and g are distinct, non-degenerate triangles given by vertex ids
// into `points`; equal ids are the same vertex, distinct ids distinct points
// (coincident vertices are refused before). True iff the closed triangles
// have a point in common other than their shared vertices and edge.
bool triangles_cross(const std::array<VertexId, 3>& f, const std::array<VertexId, 3>& g,
                     const std::vector<Point3>& points);

}  // namespace polydual
