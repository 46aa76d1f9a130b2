// What the command and the pipeline add to a check result
// (quality/check_result.h): the refusals of --require-valid and --primal, and
// the verdicts as the writers' cell arrays.
#pragma once
#include <string>
#include <vector>

#include "io/vtu_poly_writer.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"
#include "optim/tet_optimize.h"
#include "quality/check_result.h"

namespace polydual {

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

// `optimize --primal`: the classified tet mesh read from the file or, when
// mesh's cells name vertices past the file's (the interior points of
// convert's tet stage, optim/steiner.h), that mesh after convert's tet stage
// (`tetopt`, with the ratio of an optimised dual or of one without an
// optimiser, whichever gives mesh's vertices): deterministic, so its vertices
// get the numbers and places convert gave them.
ClassifiedTetMesh primal_of_dual(const PolyMesh& mesh, ClassifiedTetMesh primal, const TetOptParams& tetopt);

// The per-cell arrays the writers store beside the mesh ("valid", "bad_tets").
std::vector<CellField> verdict_fields(const std::vector<CellVerdict>& verdicts);

}  // namespace polydual
