// The parameters of the whole convert pipeline: one struct per stage, each
// owning its defaults, units and ranges (see docs/design.md, "Parameters").
// PipelineParams only groups them; validate() checks every stage's struct and
// to_json() is what every output's summary records.
#pragma once
#include "classify/classify.h"
#include "core/json.h"
#include "dual/build_dual.h"
#include "optim/optimize.h"
#include "optim/tet_optimize.h"
#include "split/split.h"

namespace polydual {

struct PipelineParams {
  // The optimiser's method is Auto (optim/optimize.h): local on tet meshes,
  // untangling only on mixed meshes.
  PipelineParams() { optim.method = OptimParams::Method::Auto; }

  ClassifyParams classify;  // feature angle of the inference
  TetOptParams tetopt;      // kappa optimisation of the input tets (enabled = false skips the stage)
  DualParams dual;          // Algorithm 1 and its cleanup
  OptimParams optim;        // untangling and smoothing (method None skips the stage)
  SplitParams split;        // split of the cells still invalid (enabled = false skips the stage)

  // The dual's boundary mode and the optimisers' matching constraints
  // (DualParams::boundary, OptimParams::keep_boundary, and
  // TetOptParams::move_curved off in the keep mode: the tets keep the
  // model's shape where the dual promises each material's volume) together.
  void set_boundary(BoundaryMode m) {
    dual.boundary = m;
    optim.keep_boundary = m == BoundaryMode::Keep;
    tetopt.move_curved = m == BoundaryMode::Caps;
  }

  // Throws UsageError naming the first bad field, its unit and its range, or
  // a boundary mode the optimiser's constraints do not follow.
  void validate() const;
  Json to_json() const;
};

}  // namespace polydual
