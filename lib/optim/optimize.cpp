#include "optim/optimize.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/interrupt.h"
#include "optim/context.h"
#include "quality/star_verdict.h"

namespace polydual {
namespace optim_detail {

Context::Context(PolyMesh& m, const ClassifiedTetMesh* primal, const OptimParams& p)
    : mesh(m), params(p), stencil(build_stencil(m)), start(std::chrono::steady_clock::now()) {
  if (primal) bc = std::make_unique<BoundaryConstraints>(*primal, m);
  dof.assign(m.num_points(), 0);
  for (std::size_t i = 0; i < m.num_points(); ++i) {
    const int d = m.point_class[i].dim;
    // Unclassified points (dim -1) and model vertices stay fixed.
    dof[i] = d == 3 ? 3 : (bc && (d == 1 || d == 2) ? static_cast<std::uint8_t>(bc->dof(PointId(i))) : 0);
  }
  // Points that lie in no cell do not enter the objective: keep them fixed.
  for (std::size_t i = 0; i < m.num_points(); ++i)
    if (stencil.cells_of(PointId(i)).empty()) dof[i] = 0;
  V0 = cell_reference_volumes(stencil, p.metric, m.points);
  cell_valid.assign(m.num_cells(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.num_cells(), 256), [&](const auto& r) {
    std::vector<Point3> scratch;
    for (std::size_t c = r.begin(); c != r.end(); ++c)
      cell_valid[c] = star_shaped_verdict(stencil, static_cast<std::uint32_t>(c), m.points, true, scratch).valid;
  });
}

double Context::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double Context::objective(std::span<const Point3> pts) const {
  std::vector<double> e(stencil.num_cells());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, e.size(), 256), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c)
      e[c] = cell_energy(stencil, static_cast<std::uint32_t>(c), params.metric, pts, V0[c], params.c);
  });
  double sum = 0;
  for (double x : e) sum += x;
  return sum;
}

void Context::record(int iteration) {
  throw_if_interrupted();  // between iterations: Ctrl-C stops a long run promptly
  IterationRecord r;
  r.iteration = iteration;
  r.objective = objective(mesh.points);
  r.invalid = count_invalid_cells(stencil, mesh.points);
  const QualityStats st = quality_stats(cell_qualities(stencil, params.metric, mesh.points), params.metric);
  r.min_quality = st.min;
  r.mean_quality = st.mean;
  r.seconds = seconds();
  report->iterations.push_back(r);
  if (progress && *progress) {
    char detail[128];
    std::snprintf(detail, sizeof detail, "invalid cells %zu, mean quality %.4f, min %.4f", r.invalid,
                  r.mean_quality, r.min_quality);
    (*progress)(ProgressEvent{"optimize", iteration, params.max_iter, r.seconds, detail});
  }
}

void Context::basis(PointId p, Vec3 B[3]) const {
  if (dof[p.idx] == 3) {
    B[0] = {1, 0, 0}; B[1] = {0, 1, 0}; B[2] = {0, 0, 1};
  } else if (dof[p.idx] > 0) {
    bc->tangent_basis(p, B);
  }
}

}  // namespace optim_detail

OptimReport optimize(PolyMesh& mesh, const ClassifiedTetMesh* primal, const OptimParams& params,
                     const ProgressFn& progress) {
  OptimReport rep;
  optim_detail::Context ctx(mesh, primal, params);
  ctx.report = &rep;
  ctx.progress = &progress;
  const auto q0 = cell_qualities(ctx.stencil, params.metric, mesh.points);
  rep.before = quality_stats(q0, params.metric);
  ctx.record(0);
  rep.invalid_before = static_cast<int>(rep.iterations.front().invalid);
  if (params.method == OptimParams::Method::Local) optim_detail::run_local(ctx);
  if (params.method == OptimParams::Method::Global) optim_detail::run_global(ctx);
  rep.after = quality_stats(cell_qualities(ctx.stencil, params.metric, mesh.points), params.metric);
  rep.invalid_after = static_cast<int>(count_invalid_cells(ctx.stencil, mesh.points));
  rep.seconds = ctx.seconds();
  return rep;
}

Json IterationRecord::to_json() const {
  Json j = Json::object();
  j.set("iteration", iteration);
  j.set("objective", objective);
  j.set("invalid", invalid);
  j.set("min_quality", min_quality);
  j.set("mean_quality", mean_quality);
  j.set("seconds", seconds);
  j.set("visited", static_cast<unsigned long long>(visited));
  j.set("updates", static_cast<unsigned long long>(updates));
  return j;
}

Json OptimReport::to_json() const {
  Json j = Json::object();
  Json it = Json::array();
  for (const auto& r : iterations) it.push(r.to_json());
  j.set("iterations", std::move(it));
  j.set("invalid_before", invalid_before);
  j.set("invalid_after", invalid_after);
  j.set("quality_before", before.to_json());
  j.set("quality_after", after.to_json());
  j.set("seconds", seconds);
  j.set("vertex_updates", static_cast<unsigned long long>(vertex_updates));
  j.set("colours", static_cast<unsigned long long>(colours));
  j.set("vertex_updates_per_second", seconds > 0 ? static_cast<double>(vertex_updates) / seconds : 0.0);
  return j;
}

namespace {
template <class T>
void require_range(const char* field, T v, T lo, T hi, const char* unit) {
  if (!(v >= lo && v <= hi))
    throw UsageError(std::string("optimiser parameter ") + field + " = " + std::to_string(v) + " is outside [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]" + (*unit ? " " : "") + unit);
}
}  // namespace

void OptimParams::validate() const {
  require_range("max_iter", max_iter, 0, kMaxIterLimit, "iterations");
  require_range("tol", tol, 0.0, kMaxTol, "(relative objective change)");
  require_range("c", c, kMinDeltaC, kMaxDeltaC, "(eq. 3)");
  require_range("newton_steps", newton_steps, 1, kMaxNewtonSteps, "steps per visit");
  require_range("settle_move", settle_move, 0.0, 1.0, "(relative to cbrt(V0))");
  require_range("untangle_sweeps", untangle_sweeps, 0, kMaxUntangleSweeps, "sweeps");
  require_range("max_halvings", max_halvings, 0, kMaxHalvings, "halvings");
  require_range("fd_step", fd_step, 1e-12, kMaxFdStep, "(relative to cbrt(V0))");
  require_range("global_iterations_per_round", global_iterations_per_round, 1, kMaxIterLimit, "iterations");
}

Json OptimParams::to_json() const {
  Json j = Json::object();
  j.set("method", method_name(method));
  j.set("metric", metric == Metric::Q1 ? "q1" : "q2");
  j.set("derivatives", derivatives_name(derivatives));
  j.set("max_iter", max_iter);
  j.set("tol", tol);
  j.set("c", c);
  j.set("newton_steps", newton_steps);
  j.set("settle_move", settle_move);
  j.set("untangle_sweeps", untangle_sweeps);
  j.set("max_halvings", max_halvings);
  j.set("fd_step", fd_step);
  j.set("global_iterations_per_round", global_iterations_per_round);
  return j;
}

OptimParams::Method parse_method(std::string_view s) {
  if (s == "none") return OptimParams::Method::None;
  if (s == "local") return OptimParams::Method::Local;
  if (s == "global") return OptimParams::Method::Global;
  throw UsageError("unknown optimisation method '" + std::string(s) + "' (expected none|local|global)");
}

Metric parse_metric(std::string_view s) {
  if (s == "q1") return Metric::Q1;
  if (s == "q2") return Metric::Q2;
  throw UsageError("unknown quality metric '" + std::string(s) + "' (expected q1|q2)");
}

OptimParams::Derivatives parse_derivatives(std::string_view s) {
  if (s == "fd") return OptimParams::Derivatives::FiniteDifference;
  if (s == "exact") return OptimParams::Derivatives::Exact;
  if (s == "analytic") return OptimParams::Derivatives::Analytic;
  throw UsageError("unknown derivatives '" + std::string(s) + "' (expected analytic|fd|exact)");
}

const char* method_name(OptimParams::Method m) {
  return m == OptimParams::Method::None ? "none" : (m == OptimParams::Method::Local ? "local" : "global");
}
const char* derivatives_name(OptimParams::Derivatives d) {
  return d == OptimParams::Derivatives::Exact ? "exact"
         : (d == OptimParams::Derivatives::Analytic ? "analytic" : "fd");
}

}  // namespace polydual
