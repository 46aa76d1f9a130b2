// The split stage (design §8, "every cell valid, certified"): cells that no
// point placement makes star-shaped (slit cells at fracture tips, cells at
// sheet crossings and at concave model edges and vertices) are split by
// rebuilding the dual with virtual cuts at their primal vertices
// (split/cuts.h, dual/vertex_cuts.h). The loop (pipeline/convert.cpp, proof
// and guarantees in proofs/split.md):
//   round 0: free-edge cuts for every slit vertex before the first dual;
//   round k: vertices of cells still invalid after optimise + check escalate
//            one level (plane cuts, then fallback: one cell per tet), the dual
//            is rebuilt with the union of all cuts, warm-started from the
//            previous optimised positions (split/warm_start.h), optimised and
//            checked again; at most max_rounds rounds.
#pragma once
#include "core/json.h"

namespace polydual {

struct SplitParams {
  // Split (default on). Off (`--no-split`): the dual without cuts, as before.
  bool enabled = true;
  // Most rebuild rounds after the first optimised dual. Two escalation levels
  // exist (plane, fallback), so 2 rounds reach the fallback everywhere.
  // Default 0 (`--split-rounds N` to try them): on every mesh measured so far
  // the rounds ended with as many invalid cells as round 0 or more (the
  // points they insert into the neighbours' faces invalidate neighbours; the
  // loop keeps the best round), at the cost of one more optimisation each.
  // Range [0, kMaxRounds].
  int max_rounds = 0;
  // Any cell still invalid at the end is an error (InputError naming each
  // cell, its primal vertex and its classification); nothing is written.
  bool require_valid = false;
  static constexpr int kMaxRounds = 16;

  // Throws UsageError naming the bad field and its range.
  void validate() const;
  Json to_json() const;
};

}  // namespace polydual
