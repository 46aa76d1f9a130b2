// What a dual rebuilt with more cuts (split/split.h) inherits from the
// previous one.
#pragma once
#include <cstddef>
#include <vector>

#include "dual/vertex_cuts.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"

namespace polydual {

// Moves every point of `fresh` whose primal origin (PolyMesh::point_origin)
// names exactly one point of `old` to that point's position; new points and
// origins shared by several old points keep their initial positions. Returns
// the number of points moved. Both meshes must carry point_origin (else 0).
// Points pinned by a whole-cut vertex of `cuts` (dual/cut_topology.h) keep
// their barycentric positions.
// from_old (may be null): per point of `fresh`, the point of `old` made from
// the same origin when that origin names exactly one point in each mesh
// (pinned or not), else invalid: a one-to-one map between the two meshes'
// points (split/recheck.h compares cells through it).
std::size_t warm_start(PolyMesh& fresh, const PolyMesh& old, const ClassifiedTetMesh& m, const VertexCuts& cuts,
                       std::vector<PointId>* from_old = nullptr);

// cell_origin of a dual built with `cuts`: for each cell, the cell of the dual
// without cuts that holds the same tets of the same primal vertex (each cut
// side lies in one uncut side). Empty if mesh's cells are not the sides of
// (m, cuts) (a mesh that was not built from m).
std::vector<CellId> cut_cell_origins(const ClassifiedTetMesh& m, const VertexCuts& cuts, const PolyMesh& mesh);

// The same origins for the dual that build_dual(m, params, stats, &cuts) will
// return, before it is built: its cells are the sides of (m, cuts) in the
// order cut_cell_origins reads them (dual/sides.h, the builder's numbering),
// whatever the DualParams. Computed while no dual is alive, so the two side
// tables are not held next to the whole dual (the split's memory peak).
std::vector<CellId> cut_cell_origins(const ClassifiedTetMesh& m, const VertexCuts& cuts);

}  // namespace polydual
