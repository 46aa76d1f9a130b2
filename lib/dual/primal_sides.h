// Sides of the vertices of a PrimalMesh (design §1, §14): the cells around v
// connected through faces on no model face. One dual cell per side, as
// dual/sides.h for tets; a vertex cut whole (the mixed split) has one side
// per cell around it.
#pragma once
#include <cstdint>
#include <vector>

#include "core/handles.h"
#include "mesh/primal_mesh.h"

namespace polydual {

struct PrimalSides {
  // corner_cell[star_off[v] + k]: the dual cell of v's side holding
  // vertex_cells(v)[k].
  std::vector<std::uint64_t> star_off;
  std::vector<CellId> corner_cell;
  // Per vertex, its one dual cell when it has one side (invalid otherwise):
  // cell() answers it without searching the star (most vertices of a
  // volume mesh are inside a region).
  std::vector<CellId> single;
  std::size_t num_cells = 0;
  // cell -> (primal vertex, PrimalMesh numbering; material)
  std::vector<VertexId> cell_vertex;
  std::vector<std::int32_t> cell_material;

  // The dual cell of the side of v that holds cell c (c must have v).
  CellId cell(const PrimalMesh& m, PrimalCellId c, VertexId v) const {
    return single[v.idx].valid() ? single[v.idx] : cell_in_star(m, c, v);
  }

 private:
  CellId cell_in_star(const PrimalMesh& m, PrimalCellId c, VertexId v) const;
};

// Cells are numbered by primal vertex, then by the first cell (in star order,
// increasing cell id) of each side: deterministic, and on a tet mesh the
// numbering compute_sides() gives for the same tet order.
// whole (per vertex, may be null): the vertices cut whole.
PrimalSides compute_primal_sides(const PrimalMesh& m, const std::vector<char>* whole = nullptr);

}  // namespace polydual
