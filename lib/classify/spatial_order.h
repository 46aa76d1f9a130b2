// Spatial renumbering of the input (design §12: cost per tet flat in the mesh
// size). Every later stage walks adjacency (edge rings, stars, face pairs); in
// the order mesh generators write their files, neighbours sit far apart in
// memory and those walks are cache misses. classify() therefore numbers
// vertices along a Morton (Z-order) curve (here) and tets by their smallest
// vertex (a counting sort in classify()); the ClassifiedTetMesh keeps the maps
// back to the input numbering.
//
// Purely combinatorial on rounded keys: the order never decides geometry, and
// it is deterministic (ties broken by input index).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/handles.h"
#include "core/vec3.h"

namespace polydual {

// order[k] = index of the point that comes k-th along the Morton curve of the
// points' bounding box (21 bits per axis).
std::vector<std::uint32_t> morton_order(const std::vector<Point3>& points);

}  // namespace polydual
