// The dual of a classified primal of any volume cell type (design §14; paper
// Algorithm 1 on tets, pyramids, prisms and hexahedra), built on PrimalMesh
// with the rules of the tet builder (dual/build_dual.h), so that on a tet mesh
// both give the same cells (tests/dual/dual_mixed_test.cpp):
//   STEP 1-4  points: each cell's central point (dual/primal_central_points.h),
//             the central point of each face on a model face, the midpoint of
//             each edge on a model edge, each model vertex; in
//             BoundaryMode::Keep also every edge and vertex on a model face;
//   sides     one dual cell per side of each vertex (dual/primal_sides.h);
//   STEP 5-6  per primal edge, per chain of cells around it
//             (PrimalMesh::edge_chains), one face per run between model faces;
//   STEP 7    caps round boundary vertices (Keep: the tiles of the model faces;
//             a quadrangle's tile is planar when the quadrangle is);
//   hints     the cleanup's (exact coincidences of tet and triangle centres,
//             short centre-to-centre edges), then cleanup_dual() and
//             assemble_cells() of the tet path.
// PolyMesh::point_origin ids are in the PrimalMesh's numbering: dim 3 a
// PrimalCellId, dim 2 a PrimalFaceId, dim 1 an EdgeId, dim 0 a VertexId.
// cell_primal is the input numbering (PrimalMesh::input_vertex).
// Whole cuts (the mixed split, design §14): a vertex v with whole[v] has one
// dual cell per cell around it, its corner: v, the midpoints of the cell's
// edges through v, the vertex means of its faces through v and of the cell
// (every face and cell through v takes its vertex mean as central point).
// Its neighbours' faces pass through those points, so the dual stays
// conformal.
#pragma once
#include "dual/build_dual.h"
#include "mesh/primal_mesh.h"

namespace polydual {

// Steps 1-7 and the hints. UsageError on bad params or a surface primal
// (dim() == 2); InputError naming the source when it is too large for
// PointOrigin ids.
// whole: per vertex (PrimalMesh numbering), cut whole; null: none.
DualDraft build_primal_dual_draft(const PrimalMesh& m, const DualParams& params = {}, DualStats* stats = nullptr,
                                  const std::vector<char>* whole = nullptr);

// params.collapse_tolerance x the mean primal edge length of m.
double primal_collapse_length(const PrimalMesh& m, const DualParams& params);

// Draft, cleanup_dual, assemble_cells; *stats gets every stage's figures.
PolyMesh build_primal_dual(const PrimalMesh& m, const DualParams& params = {}, DualStats* stats = nullptr,
                           const std::vector<char>* whole = nullptr);

// The kind of the model face `tag` of m from the regions on its sides
// (face_kind() of classified_tet_mesh.h's rule): one side External, two
// different regions Interface, the same twice Fracture. Per tag, from its
// face of least id.
std::vector<std::pair<std::int32_t, FaceKind>> primal_face_kinds(const PrimalMesh& m);

}  // namespace polydual
