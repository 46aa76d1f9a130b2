// The check result of a dual: topological and model checks (mesh/validate.h)
// joined with the exact star-shaped verdict of every cell
// (quality/star_verdict.h). The split (split/recheck.h), the pipeline and
// the command all report through it; what the command adds (refusals, the
// writers' cell arrays) is in pipeline/check.h.
#pragma once
#include <cstdint>
#include <vector>

#include "core/json.h"
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
// verdicts are computed (validation stays default). The verdicts are exact
// (the filtered star test of quality/star_verdict.h).
CheckResult check_mesh(const PolyMesh& mesh, const ClassifiedTetMesh* primal, bool with_validation = true);
// The same against any primal's reference (mesh/validate.h; a mixed primal's:
// quality/primal_reference.h).
CheckResult check_mesh(const PolyMesh& mesh, const PrimalReference& primal, bool with_validation = true);

// The same result as check_mesh(mesh, primal, true) when `known` holds the
// verdicts and per-cell exact fallbacks of this very mesh (a check_mesh of
// it, or split/recheck.h): the validation runs, the star test is not redone.
// exact_fallbacks is the sum of known.cell_exact.
CheckResult check_with_known_verdicts(const PolyMesh& mesh, const ClassifiedTetMesh* primal, CheckResult known);

}  // namespace polydual
