// The split stage (design §8, "every cell valid, certified"): replaces
// cells that no point placement makes star-shaped (slit cells at fracture tips,
// cells at sheet crossings and concave model edges) by star-shaped pieces,
// conformally and without touching any other cell's faces.
//
// Construction (proofs/split.md): the cell's half-faces are grouped so that the
// half-faces of a group share an apex X_g strictly inside all their "inner
// cones" (found by a small exact LP, CGAL QP solver). Every half-face becomes the
// pyramid cone(f, X_g), valid whatever the shape of f (split.md L1). With more
// than one group, the gap between the groups is filled by the tets
// (a, X_g, b, Y) over the boundary chain of each group, Y one more new point.
// Pyramids of one group (and the core tets) are merged into one piece when the
// merged piece passes the exact star test. Every piece is checked with the exact
// star test (decomposition_tet_sign) before the mesh is changed; a cell whose
// plan does not pass is left as it was and counted in `failed`.
#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include "core/json.h"
#include "mesh/poly_mesh.h"

namespace polydual {

struct SplitParams {
  // Split the cells that are still invalid after the optimiser. Default off
  // (`--split`): slit cells at fracture tips, the main case, find no plan yet
  // and are left as they are (counted in SplitStats::failed).
  bool enabled = false;
  // Most apex groups tried per cell (each group adds one point). Default 8,
  // range [1, kMaxGroups].
  int max_groups = 8;
  // Merge the pyramids of one group (and the core tets) into one piece when
  // the merged piece is valid by the exact test. Default on; off gives one
  // piece per half-face plus one per core tet.
  bool merge = true;
  static constexpr int kMaxGroups = 64;

  // Throws UsageError naming the bad field and its range.
  void validate() const;
  Json to_json() const;
};

struct SplitStats {
  std::size_t cells_split = 0;   // cells replaced by pieces
  std::size_t pieces = 0;        // cells made (replace cells_split cells)
  std::size_t failed = 0;        // cells given but left as they were (no valid plan)
  std::size_t new_points = 0;    // apexes and core points
  std::size_t new_faces = 0;     // triangles between pieces
  std::size_t one_group = 0;     // split cells whose half-faces share one apex
  std::size_t lp_solves = 0;     // apex and core LPs
  std::vector<CellId> failed_cells;
  double seconds = 0;
  Json to_json() const;  // counts and seconds (not the lists)
};

// Splits each given cell (duplicates ignored). Piece 0 of cell c keeps the id
// c; the other pieces are appended after the existing cells, in the order of
// `cells`. Every piece keeps the cell's material and primal vertex, and
// mesh.cell_origin (filled with the identity first if empty) records c. Faces
// of other cells are not changed (only the owner/neighbour entry naming c);
// the new points are classified in the region (dim 3, tag = material).
SplitStats split_cells(PolyMesh& mesh, std::span<const CellId> cells, const SplitParams& params = {});

}  // namespace polydual
