// A structured block of n^3 axis-aligned hex cells of size h as a PolyMesh.
// Interior points are free (dim 3). Boundary points are fixed (ModelRef{0, 0})
// unless classify_boundary: then box-face points are {2, face tag 1..6},
// box-edge points {1, edge tag}, box corners {0, corner tag}. External faces
// carry tags 1..6 (-x, +x, -y, +y, -z, +z); one material (1); no primal vertex.
#pragma once
#include "mesh/poly_mesh.h"

namespace polydual {

PolyMesh hex_block(int n, double h = 1.0, bool classify_boundary = false);

}  // namespace polydual
