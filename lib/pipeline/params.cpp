#include "pipeline/params.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace polydual {

namespace {
// ClassifyParams and DualParams ranges (their headers document the fields).
void validate_classify(const ClassifyParams& p) {
  if (!(p.feature_angle_deg > 0 && p.feature_angle_deg <= 180))
    throw UsageError("feature angle " + std::to_string(p.feature_angle_deg) + " degrees is outside (0, 180]");
}
void validate_dual(const DualParams& p) {
  if (!(p.collapse_tolerance >= 0 && p.collapse_tolerance <= 0.5))
    throw UsageError("collapse tolerance " + std::to_string(p.collapse_tolerance) +
                     " (relative to the mean primal edge) is outside [0, 0.5]");
}
}  // namespace

void PipelineParams::validate() const {
  validate_classify(classify);
  validate_dual(dual);
  optim.validate();
  split.validate();
}

Json PipelineParams::to_json() const {
  Json j = Json::object();
  j.set("feature_angle_deg", classify.feature_angle_deg);
  j.set("cleanup", dual.cleanup);
  j.set("collapse_tolerance", dual.collapse_tolerance);
  // The optimiser's fields at the top level, as the summaries always had them.
  j.set("optimize", method_name(optim.method));
  j.set("metric", optim.metric == Metric::Q1 ? "q1" : "q2");
  j.set("derivatives", derivatives_name(optim.derivatives));
  j.set("max_iter", optim.max_iter);
  j.set("optimizer", optim.to_json());
  j.set("split", split.to_json());
  return j;
}

}  // namespace polydual
