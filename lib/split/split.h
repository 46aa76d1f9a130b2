// The split stage (design §8, "every cell valid, certified"): cells that no
// point placement makes star-shaped (slit cells at fracture tips, cells at
// sheet crossings and at concave model edges and vertices) are split by
// rebuilding the dual with virtual cuts at their primal vertices
// (split/cuts.h, dual/vertex_cuts.h). The loop (pipeline/convert.cpp, proof
// and guarantees in proofs/split.md):
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
#pragma once
#include "core/json.h"

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

}  // namespace polydual
