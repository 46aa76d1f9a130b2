// Central points of the cells and faces of a PrimalMesh, one rule per type
// (design §14, paper §2.4 for simplices).
//  - tet, triangle: the rule of dual/central_points.h (circumcentre when the
//    simplex holds it, decided exactly; else clamped inside).
//  - pyramid, prism, hexahedron, quadrangle: the mean of the vertices. These
//    cells have no circumcentre in general; the mean is a convex combination
//    with positive weights, so it lies strictly inside the vertices' convex
//    hull, which is the cell when its faces are planar and it is convex; it
//    is the image of the reference element's centre under the trilinear map
//    of a hexahedron and of the bilinear map of a quadrangle. Rounded
//    coordinates; whether it is strictly inside the cell is decided EXACTLY
//    (well_centred: on the inner side of every triangle of every face fan).
#pragma once
#include "dual/central_points.h"
#include "mesh/primal_mesh.h"

namespace polydual {

CentralPoint cell_central_point(const PrimalMesh& m, PrimalCellId c);
CentralPoint face_central_point(const PrimalMesh& m, PrimalFaceId f);

}  // namespace polydual
