// Central points of the cells and faces of a PrimalMesh, one rule per type
// (design §14, paper §2.4 for simplices).
//  - tet, triangle: the rule of dual/central_points.h (circumcentre when the
//    simplex holds it, decided exactly; else clamped inside).
//  - prism: the midpoint of its two triangles' central points, which is the
//    circumcentre of a right prism (extruded layers: the dual is then the
//    extruded Voronoi diagram; laplacianFoam's error on a Gmsh boundary-layer
//    mesh 4.1e-3 with the vertex mean, 2.4e-3 with it, polyDualMesh 2.8e-3,
//    experiments/boundary_layer.py); the vertex mean when that midpoint is
//    not strictly inside (EXACT test).
//  - pyramid, hexahedron, quadrangle: the mean of the vertices. These
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
