#include "cli/convert.h"

#include <cstdio>

#include "cli/pipeline.h"
#include "core/error.h"
#include "predicates/predicates.h"

namespace polydual::cli {

ConvertOptions convert_options_from(const Args& a) {
  ConvertOptions o;
  o.classify.feature_angle_deg = a.get_double("--feature-angle", o.classify.feature_angle_deg);
  o.dual.cleanup = !a.has("--no-cleanup");
  o.dual.collapse_tolerance = a.get_double("--collapse-tol", o.dual.collapse_tolerance);
  if (o.dual.collapse_tolerance < 0 || o.dual.collapse_tolerance > 0.5)
    throw UsageError("--collapse-tol must be in [0, 0.5]");
  if (a.has("--optimize")) o.optim.method = parse_method(a.get("--optimize"));
  if (a.has("--metric")) o.optim.metric = parse_metric(a.get("--metric"));
  if (a.has("--derivatives")) o.optim.derivatives = parse_derivatives(a.get("--derivatives"));
  const long long it = a.get_int("--max-iter", o.optim.max_iter);
  if (it < 0 || it > 100000) throw UsageError("--max-iter must be in [0, 100000]");
  o.optim.max_iter = static_cast<int>(it);
  o.format = a.get("--format");
  return o;
}

static std::size_t count_invalid(const std::vector<CellVerdict>& v) {
  std::size_t n = 0;
  for (const auto& c : v) n += !c.valid;
  return n;
}

Json run_convert(const std::string& in, const std::string& out, const ConvertOptions& o) {
  const std::string format = output_format(o.format, out);
  Json seconds = Json::object();
  Timer total;
  ClassifiedTetMesh m = load_classified(in, o.classify, seconds);

  Timer td;
  DualStats ds;
  PolyMesh pm = build_dual(m, o.dual, &ds);
  seconds.set("dual", td.seconds());

  Timer tc;
  predicate_counters().reset();
  std::vector<CellVerdict> verdicts = star_shaped_verdicts(pm);
  seconds.set("star_test", tc.seconds());
  const std::size_t invalid_before = count_invalid(verdicts);
  std::uint64_t star_calls = 0;
  for (const CellVerdict& v : verdicts) star_calls += static_cast<std::uint64_t>(v.total_tets);
  const auto star_exact = predicate_counters().star_exact.load();

  Json optim = nullptr;
  if (o.optim.method != OptimParams::Method::None) {
    Timer to;
    OptimReport rep = optimize(pm, &m, o.optim);
    seconds.set("optimize", to.seconds());
    optim = rep.to_json();
    verdicts = star_shaped_verdicts(pm);
  }

  Timer tw;
  Json written = write_poly(pm, verdicts, out, format);
  seconds.set("write", tw.seconds());
  seconds.set("total", total.seconds());

  Json j = Json::object();
  j.set("input", in);
  j.set("output", written);
  j.set("tets", m.num_tets());
  j.set("vertices", m.num_vertices());
  j.set("model", model_summary(m));
  Json summary = poly_summary(pm, verdicts, &m);
  // Flatten the dual summary into the top level (cells, faces, points, ...).
  for (const char* k : {"cells", "faces", "points", "invalid_cells", "closed_cells", "slit_cells", "face_errors",
                        "negative_volume_cells", "materials", "missing_model_entities", "topology_ok",
                        "invalid_by_class", "invalid_where"})
    if (const Json* v = summary.find(k)) j.set(k, *v);
  j.set("invalid_before", invalid_before);
  j.set("invalid_after", count_invalid(verdicts));
  Json star = Json::object();
  star.set("decomposition_tets", star_calls);
  star.set("exact_fallbacks", star_exact);
  j.set("star_test", star);
  j.set("dual", ds.to_json());
  j.set("optimize", optim);
  Json params = Json::object();
  params.set("feature_angle_deg", o.classify.feature_angle_deg);
  params.set("cleanup", o.dual.cleanup);
  params.set("collapse_tolerance", o.dual.collapse_tolerance);
  params.set("optimize", method_name(o.optim.method));
  params.set("metric", o.optim.metric == Metric::Q1 ? "q1" : "q2");
  params.set("derivatives", derivatives_name(o.optim.derivatives));
  params.set("max_iter", o.optim.max_iter);
  j.set("params", params);
  j.set("seconds", seconds);
  return j;
}

void print_convert_summary(const Json& jc) {
  Json j = jc;
  auto num = [&](const char* k) { return j.find(k) ? j.find(k)->dump(0) : std::string("?"); };
  std::printf("%s -> %s\n", num("input").c_str(), j.find("output")->find("path")->dump(0).c_str());
  std::printf("  tets %s -> cells %s, faces %s, points %s\n", num("tets").c_str(), num("cells").c_str(),
              num("faces").c_str(), num("points").c_str());
  std::printf("  invalid cells (exact star test): before %s, after %s; closed cells %s; slit cells %s\n",
              num("invalid_before").c_str(), num("invalid_after").c_str(), num("closed_cells").c_str(),
              num("slit_cells").c_str());
  std::printf("  seconds %s\n", j.find("seconds")->dump(0).c_str());
}

}  // namespace polydual::cli
