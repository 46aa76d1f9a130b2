// Sides of primal vertices (SPEC §1): the tets around v connected through
// triangles not on a model face. One dual cell per side.
#pragma once
#include <vector>

#include "core/handles.h"
#include "mesh/classified_tet_mesh.h"

namespace polydual {

struct VertexSides {
  // cell_of[4*t + i]: the dual cell of the side of tet t's local vertex i.
  std::vector<CellId> cell_of;
  std::size_t num_cells = 0;
  // cell -> (primal vertex, material)
  std::vector<VertexId> cell_vertex;
  std::vector<std::int32_t> cell_material;
  CellId cell(TetId t, int local) const { return cell_of[4 * t.idx + local]; }
};

// Cells are numbered by primal vertex, then by the first tet (in star order)
// of each side: deterministic.
VertexSides compute_sides(const ClassifiedTetMesh& mesh);

}  // namespace polydual
