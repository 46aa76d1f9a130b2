// The exact star test of a rebuilt dual (a split round, split/split.h) that
// redoes only the cells that are not, point for point, a cell of the previous
// dual. Proof that a reused verdict is the one check_mesh would give:
// proofs/split.md, L4.
#pragma once
#include <cstddef>
#include <span>

#include "mesh/poly_mesh.h"
#include "quality/check_result.h"

namespace polydual {

struct RecheckStats {
  std::size_t reused = 0;     // cells whose verdict was carried over
  std::size_t rechecked = 0;  // cells tested again
};

// Whether cell c of `fresh` and cell d of `old` have the same half-face count
// and, half-face by half-face, oriented loops of the same length whose points
// correspond through from_old (fresh point -> old point, one-to-one on the
// points it maps; invalid: no partner) and have bitwise equal coordinates.
bool same_cell(const PolyMesh& fresh, CellId c, const PolyMesh& old, CellId d, std::span<const PointId> from_old);

// The verdicts (and per-cell exact fallbacks) of `fresh`, equal to those of
// check_mesh(fresh, nullptr, false): a cell of fresh that is same_cell as its
// partner in `old` takes that cell's verdict from old_check, every other cell
// is tested. Partners: cells are numbered by primal vertex, then by side
// (dual/sides.h); the k-th cell of a vertex in fresh is paired with the k-th
// of the same vertex in old when the vertex has as many cells in both.
// old_check must hold old's verdicts and cell_exact (check_mesh fills both);
// without them every cell is tested.
CheckResult recheck_mesh(const PolyMesh& fresh, const PolyMesh& old, const CheckResult& old_check,
                         std::span<const PointId> from_old, RecheckStats* stats = nullptr);

}  // namespace polydual
