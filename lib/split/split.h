// The split stage (design §8, "every cell valid, certified"): cells that no
// point placement makes star-shaped (slit cells at fracture tips, cells at
// sheet crossings and at concave model edges and vertices) are split by
// rebuilding the dual with virtual cuts at their primal vertices
// (split/cuts.h, dual/vertex_cuts.h). The loop (pipeline/convert.cpp, proof
// and guarantees in proofs/split.md):
//   round 0: free-edge cuts for every slit vertex before the first dual;
//   round k: the vertices of cells still invalid after optimise + check are
//            cut whole (the fallback: one cell per tet, the barycentric corner,
//            convex by construction: proofs/dual_cuts.md C5), the dual is
//            rebuilt with the union of all cuts, the other points
//            warm-started from the previous positions (split/warm_start.h),
//            and checked; a neighbour that the barycentric points turn
//            invalid is cut whole in the next round. The mesh kept is then
//            optimised once more. At most max_rounds rounds.
//   without an optimiser the rounds are local (split/local_round.h,
//            proofs/split.md L5): only the cells around the newly whole
//            vertices are rebuilt and tested, then one whole build with
//            every cut is checked exactly.
#pragma once
#include "core/json.h"

namespace polydual {

struct SplitParams {
  // Split (default on). Off (`--no-split`): the dual without cuts, as before.
  bool enabled = true;
  // Most rebuild rounds after the first optimised dual; 0: free-edge cuts
  // only. Each round cuts at least one more vertex whole, so the loop ends;
  // on the meshes measured it needs a few rounds (the ring of neighbours the
  // barycentric points disturb). Range [0, kMaxRounds].
  int max_rounds = 64;
  // Any cell still invalid at the end is an error (InputError naming each
  // cell, its primal vertex and its classification); nothing is written.
  bool require_valid = false;
  static constexpr int kMaxRounds = 100000;

  // Throws UsageError naming the bad field and its range.
  void validate() const;
  Json to_json() const;
};

}  // namespace polydual
