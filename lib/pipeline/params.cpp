#include "pipeline/params.h"

#include <string>

#include "core/error.h"


namespace polydual {


void PipelineParams::validate() const {
  classify.validate();
  tetopt.validate();
  dual.validate();
  optim.validate();
  split.validate();
  if (optim.keep_boundary != (dual.boundary == BoundaryMode::Keep))
    throw UsageError(std::string("PipelineParams: the dual's boundary is '") + boundary_mode_name(dual.boundary) +
                     "' but the optimiser's constraints are for '" + (optim.keep_boundary ? "keep" : "caps") +
                     "' (set both with set_boundary)");
  if (dual.boundary == BoundaryMode::Keep && tetopt.enabled && tetopt.move_curved)
    throw UsageError("PipelineParams: the keep boundary keeps each material's volume but the tet optimiser "
                     "moves vertices on curved model faces (set both with set_boundary)");
}

Json PipelineParams::to_json() const {
  Json j = Json::object();
  j.set("feature_angle_deg", classify.feature_angle_deg);
  j.set("boundary", boundary_mode_name(dual.boundary));
  j.set("cleanup", dual.cleanup);
  j.set("collapse_tolerance", dual.collapse_tolerance);
  // The optimiser's fields at the top level, as the summaries always had them.
  j.set("optimize", method_name(optim.method));
  j.set("metric", optim.metric == Metric::Q1 ? "q1" : "q2");
  j.set("derivatives", derivatives_name(optim.derivatives));
  j.set("max_iter", optim.max_iter);
  j.set("classifier", classify.to_json());
  j.set("dual_params", dual.to_json());
  j.set("optimizer", optim.to_json());
  j.set("split", split.to_json());
  j.set("tet_optimizer", tetopt.to_json());
  return j;
}

}  // namespace polydual
