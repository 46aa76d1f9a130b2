// Sides of primal vertices (design §1): the tets around v connected through
// triangles on no model face and not in v's cut set (dual/vertex_cuts.h,
// design §8). One dual cell per side.
#pragma once
#include <algorithm>
#include <vector>

#include "core/handles.h"
#include "dual/vertex_cuts.h"
#include "mesh/classified_tet_mesh.h"

namespace polydual {

struct VertexSides {
  static constexpr std::uint32_t kOneSide = 0xffffffffu;
  const ClassifiedTetMesh* mesh = nullptr;
  // first_cell[v]: the cell of v's first side (its only one unless corner_off[v]
  // is set). Vertices on model faces keep one cell per star entry:
  // corner_cell[corner_off[v] + k] is the cell of v in vertex_tets(v)[k].
  // (4 bytes per star entry only where a vertex can have several sides.)
  std::vector<std::uint32_t> first_cell, corner_off;
  std::vector<CellId> corner_cell;
  std::size_t num_cells = 0;
  // cell -> (primal vertex, material)
  std::vector<VertexId> cell_vertex;
  std::vector<std::int32_t> cell_material;

  // The dual cell of the side of v that contains tet t (t must have v).
  CellId cell(TetId t, VertexId v) const {
    const std::uint32_t off = corner_off[v.idx];
    if (off == kOneSide) return CellId(first_cell[v.idx]);
    return corner_cell[off + mesh->star_rank(v, t)];
  }
};

// Cells are numbered by primal vertex, then by the first tet (in star order)
// of each side: deterministic. cuts (null: none) must have been checked
// (cut_topology()).
VertexSides compute_sides(const ClassifiedTetMesh& mesh, const VertexCuts* cuts = nullptr);

}  // namespace polydual
