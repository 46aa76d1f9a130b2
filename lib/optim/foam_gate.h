// OpenFOAM's own geometric checks of a polyhedral cell, in floating point, as
// a second gate beside the exact star test (which decides validity, with the
// mean-point centres of paper 3.1). A solver computes other centres:
//  - face centre and area by the triangles of the loop about its point
//    average (primitiveMesh::makeFaceCentresAndAreas): area = half the sum of
//    the triangles' area vectors, centre = their centroids weighted by area;
//  - cell centre by the pyramids of its faces about the mean of its face
//    centres (primitiveMesh::makeCellCentresAndVols);
// and checkMesh -allGeometry then asks, per face (OpenFOAM v1912):
//  - face pyramids: the face's area vector points away from each of its
//    cells' centres;
//  - face tets (polyMeshTetDecomposition::checkFaceTets): every tet (a, b,
//    face centre, cell centre) over the loop's edges is correctly oriented for
//    both cells, and some loop point b is a base whose fan (b, a_i, a_i+1)
//    makes correctly oriented tets with both cells' centres.
// The second face-tet rule ties the two cells of a face together. So that a
// cell's verdict depends on its own points only (the local scheme moves the
// points of different cells in parallel), each face gets a fixed base point
// (choose_foam_bases, chosen while both centres are known), and a cell passes
// when, for each of its faces, both the centre fan and the fixed base's fan
// are correctly oriented with its own centre. A face both of whose cells pass
// passes both of OpenFOAM's rules. Inexact by design (it mirrors OpenFOAM's
// doubles); a margin kFoamMargin on the sine of each tet's apex angle keeps
// the verdict away from what rounding and ASCII output could flip.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/json.h"
#include "mesh/poly_mesh.h"
#include "quality/stencil.h"

namespace polydual {

// A tet passes when its signed volume exceeds kFoamMargin x |base triangle's
// doubled area| x |apex - base point| (the sine of the apex's elevation).
inline constexpr double kFoamMargin = 1e-6;

// OpenFOAM's face centre of a loop (its points in order); *area gets the
// area vector (right-hand normal of the loop, length = area).
Point3 foam_face_centre(std::span<const PointId> loop, std::span<const Point3> points, Vec3* area);
// OpenFOAM's cell centre of stencil cell c (its loops outward).
Point3 foam_cell_centre(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points);

// Per stencil loop, the mesh face it is (loop j of cell c is mesh.cell(c)[j - cell_loop_off[c]]).
std::vector<std::uint32_t> stencil_loop_faces(const PolyMesh& mesh, const MeshStencil& s);

// Per mesh face, a base point for the vertex fan: the first loop point whose
// fan passes with both cells' centres (with twice the margin), else the one
// whose worst tet is best. With `base` non-empty (one per face) only the
// faces for which some base passes get a new one; the others keep theirs.
void choose_foam_bases(const PolyMesh& mesh, const MeshStencil& s, std::span<const Point3> points,
                       std::vector<PointId>& base);

// Whether cell c passes (above) with the faces' bases base[loop_face[j]];
// `centre` (may be null) gets its OpenFOAM centre.
bool foam_cell_ok(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points,
                  std::span<const PointId> base, std::span<const std::uint32_t> loop_face, Point3* centre = nullptr);
// How far cell c is from passing: the sum over its failing tets of
// (2 kFoamMargin - sine), 0 when every tet has twice the margin. A
// continuous measure for the repair's descent.
double foam_cell_violation(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points,
                           std::span<const PointId> base, std::span<const std::uint32_t> loop_face);

// OpenFOAM's verdict on a whole mesh, with any base point (as checkMesh):
// faces with a wrongly oriented pyramid, faces failing the face-tet check,
// and the cells next to them (increasing).
struct FoamCheck {
  std::size_t pyramid_faces = 0, face_tet_faces = 0;
  std::vector<std::uint32_t> cells;
  Json to_json() const;
};
FoamCheck foam_check(const PolyMesh& mesh);

}  // namespace polydual
