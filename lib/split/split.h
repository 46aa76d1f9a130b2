// The split stage (design §8, "every cell valid, certified"): cells that no
// point placement makes star-shaped (slit cells at fracture tips, cells at
// sheet crossings and at concave model edges and vertices) are split by
// rebuilding the dual with virtual cuts at their primal vertices
// (split/cuts.h, dual/vertex_cuts.h). The loop (run_split below; proof and
// guarantees in proofs/split.md):
//   round 0: free-edge cuts for every slit vertex before the first dual;
//   round k: the vertices of cells still invalid after optimise + check are
//            cut whole (the fallback: one cell per tet, the barycentric
//            corner, convex by construction: proofs/dual_cuts.md C5), the
//            dual is rebuilt with the union of all cuts, the other points
//            warm-started from the previous positions (split/warm_start.h),
//            checked, and (with an optimiser) untangled near the newly pinned
//            points, so that the neighbours the barycentric points disturb
//            are moved back to validity rather than cut. At most max_rounds.
//   closure: rounds without optimisation, every pinned point at its
//            barycentre, cutting whole the vertices of the cells still
//            invalid until every invalid cell is a whole vertex's corner:
//            at most |V| + 1 rounds, ending with 0 invalid cells (at worst
//            the barycentric subdivision; proofs/split.md T1). The mesh
//            kept is then optimised once more.
//   without an optimiser the rounds are local (split/local_round.h,
//            proofs/split.md L5): only the cells around the newly whole
//            vertices are rebuilt and tested, then one whole build with
//            every cut is checked exactly.
//
// A driver calls begin_split before the first dual (its free-edge cuts are
// that dual's), builds, checks and optimises the first dual itself, then
// calls run_split; the pipeline (pipeline/convert.cpp) is one such driver.
#pragma once
#include <functional>
#include <span>
#include <vector>

#include "core/json.h"
#include "core/progress.h"
#include "dual/build_dual.h"
#include "dual/vertex_cuts.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"
#include "quality/check_result.h"
#include "quality/metrics.h"
#include "split/cuts.h"

namespace polydual {

struct SplitParams {
  // Split (default on). Off (`--no-split`): the dual without cuts, as before.
  bool enabled = true;
  // Most optimised rebuild rounds after the first optimised dual; the
  // closure that follows them (proofs/split.md T1) is bounded by the mesh,
  // not by this. 0: free-edge cuts only, no closure (cells may stay
  // invalid: warned, or refused with require_valid). Range [0, kMaxRounds].
  int max_rounds = 64;
  // Any cell still invalid at the end is an error (InputError naming each
  // cell, its primal vertex and its classification); nothing is written.
  bool require_valid = false;
  // After the rounds, merge the barycentric corners of the whole vertices
  // back while every cell stays valid (split/coarsen.h). Off
  // (`--no-coarsen`): one cell per tet at every whole vertex.
  bool coarsen = true;
  static constexpr int kMaxRounds = 100000;

  // Throws UsageError naming the bad field and its range.
  void validate() const;
  Json to_json() const;
};

// The split's state between its calls: per primal vertex (internal
// numbering) whether it is cut whole (the fallback, one cell per tet) and the
// cause it was first cut for.
struct SplitState {
  VertexCuts free_edge, cuts;  // cuts: the union used by the current dual
  std::vector<char> whole;
  std::vector<CutCause> cause;
  std::vector<VertexId> internal_of_input;  // cell_primal (input numbering) -> internal
};

// Round 0: the free-edge cuts of every slit vertex (split/cuts.h), which the
// first dual is to be built with (free_edge == cuts), no vertex whole.
SplitState begin_split(const ClassifiedTetMesh& m);

// The optimiser as the split sees it (the split does not know its method):
// moves mesh's points in place, starting from `verdicts` (mesh's exact
// verdicts as it is), near the cells marked in `seed` (per cell; the
// optimiser may ignore it and move every point). untangle_only: the rounds'
// untangling, whose result only decides the next round's cuts; otherwise the
// full method, on the mesh kept. Returns the optimiser's record. It must
// leave every valid cell valid (the optimiser's exact gate).
using SplitOptimiser = std::function<Json(PolyMesh& mesh, std::span<const char> seed,
                                          std::span<const CellVerdict> verdicts, bool untangle_only)>;

// The cells of a mesh that OpenFOAM's own checks fail, increasing.
using FoamFailing = std::function<std::vector<std::uint32_t>(const PolyMesh&)>;

struct SplitHooks {
  SplitOptimiser optimise;  // empty: no optimiser (the rounds are local, split/local_round.h)
  ProgressFn progress;      // after each round ("split", round, invalid cells)
  // The quality measure the coarsening bounds merged cells with (split/coarsen.h):
  // the optimiser's, so that the bound is the one its report counts against.
  Metric metric = Metric::Q1;
  // The cells that OpenFOAM's own checks fail (face pyramids, face tets:
  // optim/foam_gate.h's foam_check), increasing; empty: not asked. With an
  // optimiser, the vertices of the cells the kept mesh still fails after
  // its re-optimisation are cut whole too (SplitLoop::foam_rounds).
  FoamFailing foam_failing;
  // The full method with OpenFOAM's checks gating every move
  // (OptimParams::foam_gate_sweeps), to smooth cells re-pinned for those
  // checks without failing them again (untangle_only is false). Empty: not
  // run.
  SplitOptimiser optimise_foam_gated;
};

// The rounds after the first dual (the loop above): `mesh` is the first dual
// (built with st.cuts == st.free_edge, optimised when hooks.optimise is set)
// and `check` its exact verdicts (validation not needed). On return `mesh` is
// the mesh kept (the one with the fewest invalid cells, the earliest among
// equals: proofs/split.md T2), re-optimised near its cuts when it is a split
// one, with cell_origin set when it has cuts; `check` holds its verdicts
// (not its validation); st.cuts its cuts. Returns the stage's record (rounds,
// kept round, closure rounds, cells split by cause). Throws Interrupted
// between rounds.
Json run_split(const ClassifiedTetMesh& m, const DualParams& dual, const SplitParams& params, SplitState& st,
               PolyMesh& mesh, CheckResult& check, const SplitHooks& hooks);

}  // namespace polydual
