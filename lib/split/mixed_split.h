// The split of a mixed dual (design §14, proofs/mixed_dual.md M4): rounds of
// whole cuts at the primal vertices of the cells that stay invalid. A vertex
// cut whole has one dual cell per primal cell around it, the barycentric
// corner (the vertex, its edges' midpoints, its faces' and the cell's vertex
// means: dual/primal_dual.h); each round rebuilds the dual with every cut so
// far, keeps the optimised points that no cut touches (warm start) and
// re-optimises around the cuts. Unlike the tet split (split/split.h) there
// are no partial cuts, no closure and no coarsening yet.
//
// The corner is convex for a tet, and for any convex cell with planar
// faces, in exact arithmetic; its points are rounded and the re-optimisation
// may move them, and a prism or hexahedron with warped quadrilaterals has
// corners that need not be star-shaped: a cell may stay invalid, which the
// caller reports (or refuses with require_valid).
#pragma once
#include <vector>

#include "core/json.h"
#include "dual/build_dual.h"
#include "mesh/poly_mesh.h"
#include "mesh/primal_mesh.h"
#include "quality/check_result.h"
#include "split/split.h"

namespace polydual {

// The rounds after the first, optimised dual of m: `mesh` is that dual and
// `check` its exact verdicts. Each round cuts whole the primal vertices of
// the invalid cells not cut yet; the loop stops when no cell is invalid, a
// round cuts nothing new, or after params.max_rounds rounds. hooks.optimise
// (required) re-optimises each rebuilt dual near the cells of the vertices cut
// whole (untangle_only false: the last round's mesh is the one kept). On
// return `mesh` is the last round's dual and `check` its verdicts (not its
// validation). With hooks.foam_failing, the vertices of cells that
// OpenFOAM's checks still fail are then cut whole too (at most three rounds,
// each undone if it leaves a cell invalid; counted as one more round).
// Returns the rounds run (0: mesh and check unchanged) and the
// stage's record (rounds, whole_vertices, invalid_before/after,
// cells_before/after). Throws Interrupted between rounds.
struct MixedSplitRun {
  int rounds = 0;
  Json stats;
};
MixedSplitRun run_mixed_split(const PrimalMesh& m, const DualParams& dual, const SplitParams& params,
                              PolyMesh& mesh, CheckResult& check, const SplitHooks& hooks);

// The rebuilt dual `after` takes the points of `before` (a dual of the same
// primal) wherever a point has the same origin and touches no vertex cut
// whole (per internal vertex, `whole`): those keep the builder's barycentric
// positions. Returns the number of points moved.
std::size_t warm_start_whole(const PrimalMesh& m, const std::vector<char>& whole, const PolyMesh& before,
                             PolyMesh& after);

}  // namespace polydual
