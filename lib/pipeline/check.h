// The validity stage: topological and model checks (mesh/validate.h) joined
// with the exact star-shaped verdict of every cell (quality/star_verdict.h).
// `check`, `optimize`, `convert` and the demo all report through it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/json.h"
#include "io/vtu_poly_writer.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"
#include "mesh/validate.h"
#include "quality/star_verdict.h"

namespace polydual {

struct CheckResult {
  ValidationReport validation;
  std::vector<CellVerdict> verdicts;  // one per cell, exact
  std::size_t invalid_cells = 0;      // cells whose verdict is not valid
  std::uint64_t decomposition_tets = 0;  // star-test tets evaluated
  std::uint64_t exact_fallbacks = 0;     // of which reached the exact path
  std::vector<std::uint32_t> cell_exact;  // per cell, its exact fallbacks (empty: not known)
  double seconds = 0;
  Json to_json() const;  // counts only (the verdicts go into the cell data)
};

// primal may be null (a mesh read back from a file): model entities and the
// primal volumes are then not checked. Without `with_validation` only the
// verdicts are computed (validation stays default).
CheckResult check_mesh(const PolyMesh& mesh, const ClassifiedTetMesh* primal, bool with_validation = true);

// The same result as check_mesh(mesh, primal, true) when `known` holds the
// verdicts and per-cell exact fallbacks of this very mesh (a check_mesh of
// it, or split/recheck.h): the validation runs, the star test is not redone.
// exact_fallbacks is the sum of known.cell_exact.
CheckResult check_with_known_verdicts(const PolyMesh& mesh, const ClassifiedTetMesh* primal, CheckResult known);

// --require-valid for a mesh checked on its own (`optimize`): an InputError
// naming `source`, the validation's failed checks and the cells still
// invalid (at most 100), unless there is neither.
void require_valid_mesh(const CheckResult& c, const std::string& source);

// `optimize --primal`: whether `primal` is the tet mesh `mesh` (read from
// `mesh_source`) is the dual of, else an InputError naming both files:
//  - the vertices match both ways (input numbering): every cell's primal
//    vertex is one of the primal's, every primal vertex has a cell;
//  - exactly (== on each coordinate): every dual point on a model vertex (class dim 0,
//    which no stage moves) is at the primal vertex of one of its cells;
//  - every primal vertex lies in its cells' bounding box grown by the box's
//    own size on each side (a dual cell surrounds its vertex; a coarse test
//    for the cells whose vertex is no dual point).
void require_primal_of(const PolyMesh& mesh, const std::string& mesh_source, const ClassifiedTetMesh& primal);

// The per-cell arrays the writers store beside the mesh ("valid", "bad_tets").
std::vector<CellField> verdict_fields(const std::vector<CellVerdict>& verdicts);

}  // namespace polydual
