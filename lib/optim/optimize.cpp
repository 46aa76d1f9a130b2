#include "optim/optimize.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/param_range.h"
#include "optim/context.h"
#include "optim/foam_gate.h"
#include "optim/objective.h"
#include "quality/star_verdict.h"

namespace polydual {
namespace optim_detail {

namespace {
// The local schemes move only the points they visit and ensure() each
// first (VertexNewton::optimise): their initial primitives are found then.
std::unique_ptr<BoundaryConstraints> make_constraints(const ModelFacets* facets, const PolyMesh& m,
                                                      const OptimParams& p) {
  if (!facets) return nullptr;
  return std::make_unique<BoundaryConstraints>(*facets, m, p.method != OptimParams::Method::Global, p.keep_boundary);
}
}  // namespace

RunSetup Context::set_up(const OptimParams& p, std::span<const char> seeds) {
  lap("constraints");  // bc, built before the set-up
  RunSetup s{p, build_stencil(mesh, p.method == OptimParams::Method::Global), {}, {}, seeds, {}};
  lap("stencil");  // (Global: its gradients need loop_local)
  s.dof.assign(mesh.num_points(), 0);
  for (std::size_t i = 0; i < mesh.num_points(); ++i) {
    const int d = mesh.point_class[i].dim;
    // Unclassified points (dim -1) and model vertices stay fixed.
    s.dof[i] = d == 3 ? 3 : (bc && (d == 1 || d == 2) ? static_cast<std::uint8_t>(bc->dof(PointId(i))) : 0);
  }
  // Points that lie in no cell do not enter the objective: keep them fixed.
  for (std::size_t i = 0; i < mesh.num_points(); ++i)
    if (s.stencil.cells_of(PointId(i)).empty()) s.dof[i] = 0;
  const bool untangling = p.method == OptimParams::Method::Untangle;
  s.V0 = untangling ? cell_reference_volumes(s.stencil, p.metric, mesh.points, &cell_quality)
                    : cell_reference_volumes(s.stencil, p.metric, mesh.points);
  lap("reference_volumes");
  const bool local = p.method == OptimParams::Method::Local || untangling;
  if (p.foam_gate && local) {
    s.loop_face = stencil_loop_faces(mesh, s.stencil);
    lap("foam_gate");
  }
  return s;
}

Context::Context(PolyMesh& m, const ModelFacets* facets, const OptimParams& p, std::span<const char> seeds,
                 std::span<const CellVerdict> known)
    : mesh(m),
      start(std::chrono::steady_clock::now()),
      lap_start(start),
      bc(make_constraints(facets, m, p)),
      setup(set_up(p, seeds)) {
  // Untangling: the qualities are those of the points as they are (set_up).
  all_touched = records_energy();
  touched.assign(m.num_points(), 0);
  cell_valid.assign(m.num_cells(), 0);
  if (known.size() == m.num_cells()) {
    for (std::size_t c = 0; c < known.size(); ++c) cell_valid[c] = known[c].valid;
    lap("verdicts");
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.num_cells(), 256), [&](const auto& r) {
    std::vector<Point3> scratch;
    for (std::size_t c = r.begin(); c != r.end(); ++c)
      cell_valid[c] =
          star_shaped_verdict(setup.stencil, static_cast<std::uint32_t>(c), m.points, true, scratch).valid;
  });
  lap("verdicts");
}

void Context::lap(const char* name) {
  const auto now = std::chrono::steady_clock::now();
  const double dt = std::chrono::duration<double>(now - lap_start).count();
  lap_start = now;
  auto& phases = report ? report->phases : setup_phases;
  for (auto& [n, t] : phases)
    if (n == name) { t += dt; return; }
  phases.emplace_back(name, dt);
}

double Context::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double Context::objective(std::span<const Point3> pts) const {
  std::vector<double> e(setup.stencil.num_cells());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, e.size(), 256), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c)
      e[c] = cell_energy(setup.stencil, static_cast<std::uint32_t>(c), setup.params.metric, pts, setup.V0[c], setup.params.c);
  });
  double sum = 0;
  for (double x : e) sum += x;
  return sum;
}

bool Context::uses_centre_gradients() const {
  return setup.params.derivatives == OptimParams::Derivatives::Corrected && setup.params.method != OptimParams::Method::Untangle;
}

namespace {
// The cells to re-evaluate at a record (every cell when all points count as
// touched, else the cells of the touched points, increasing); clears the marks.
std::vector<std::uint32_t> changed_cells(Context& ctx) {
  const std::size_t nc = ctx.setup.stencil.num_cells();
  std::vector<std::uint32_t> cells;
  if (ctx.all_touched) {
    cells.resize(nc);
    for (std::size_t c = 0; c < nc; ++c) cells[c] = static_cast<std::uint32_t>(c);
  } else {
    std::vector<char> dirty(nc, 0);
    for (std::size_t p = 0; p < ctx.touched.size(); ++p)
      if (ctx.touched[p])
        for (std::uint32_t c : ctx.setup.stencil.cells_of(PointId(p))) dirty[c] = 1;
    for (std::size_t c = 0; c < nc; ++c)
      if (dirty[c]) cells.push_back(static_cast<std::uint32_t>(c));
  }
  ctx.all_touched = false;
  std::fill(ctx.touched.begin(), ctx.touched.end(), 0);
  return cells;
}
}  // namespace

void Context::refresh_cells(std::span<const std::uint32_t> cells) {
  const bool grads = uses_centre_gradients();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 64), [&](const auto& rg) {
    for (std::size_t i = rg.begin(); i != rg.end(); ++i) {
      const std::uint32_t c = cells[i];
      if (!records_energy()) {
        cell_quality[c] = polydual::cell_quality(setup.stencil, c, setup.params.metric, mesh.points);
      } else if (grads) {
        recorded_energy[c] = cell_energy_gradient(setup.stencil, c, setup.params.metric, mesh.points, setup.V0[c], setup.params.c, nullptr,
                                                  &grad_R[c], grad_F.data() + setup.stencil.cell_loop_off[c]);
        cell_quality[c] = polydual::cell_quality(setup.stencil, c, setup.params.metric, mesh.points);
      } else {
        recorded_energy[c] =
            cell_energy_and_quality(setup.stencil, c, setup.params.metric, mesh.points, setup.V0[c], setup.params.c, &cell_quality[c]);
      }
    }
  });
}

void Context::record(int iteration) {
  throw_if_interrupted();  // between iterations: Ctrl-C stops a long run promptly
  if (iteration > 0) lap("iterations");
  IterationRecord r;
  r.iteration = iteration;
  // The cells whose points moved since the last record get their energy and
  // quality (and, with the centre gradients, grad_R and grad_F: the next
  // sweep's corrected model needs them current) from one pass over their
  // corners; the others keep theirs. The sums are serial in cell order, so
  // the objective is the same as a full pass's, bit for bit.
  const std::size_t nc = setup.stencil.num_cells();
  if (records_energy()) recorded_energy.resize(nc);
  cell_quality.resize(nc);
  if (uses_centre_gradients()) {
    grad_R.resize(nc);
    grad_F.resize(setup.stencil.cell_loop_off.back());
  }
  refresh_cells(changed_cells(*this));
  r.objective = records_energy() ? 0.0 : std::numeric_limits<double>::quiet_NaN();
  for (double e : recorded_energy) r.objective += e;
  // cell_valid holds the exact star verdict of every cell at all times (both
  // schemes re-test every cell whose points they move), so counting it is the
  // exact count without a second pass of the star test.
  r.invalid = 0;
  for (std::uint8_t v : cell_valid) r.invalid += v == 0;
  last_stats = quality_stats(cell_quality, setup.params.metric);
  for (std::size_t c = 0; c < nc; ++c) last_stats.degenerate += cell_valid[c] && !std::isfinite(cell_quality[c]);
  // The cap of the next sweep's moves: the worst valid cell now.
  quality_cap = 0;
  for (std::size_t c = 0; c < nc; ++c)
    if (cell_valid[c] && std::isfinite(cell_quality[c])) quality_cap = std::max(quality_cap, cell_quality[c]);
  r.min_quality = last_stats.min;
  r.mean_quality = last_stats.mean;
  r.max_quality = last_stats.max;
  r.seconds = seconds();
  report->iterations.push_back(r);
  lap("record");
  if (progress && *progress) {
    char detail[128];
    std::snprintf(detail, sizeof detail, "invalid cells %zu, mean quality %.4f, min %.4f", r.invalid,
                  r.mean_quality, r.min_quality);
    (*progress)(ProgressEvent{"optimize", iteration, setup.params.max_iter, r.seconds, detail});
  }
}

void Context::basis(PointId p, Vec3 B[3]) const {
  if (setup.dof[p.idx] == 3) {
    B[0] = {1, 0, 0}; B[1] = {0, 1, 0}; B[2] = {0, 0, 1};
  } else if (setup.dof[p.idx] > 0) {
    bc->tangent_basis(p, B);
  }
}

}  // namespace optim_detail

OptimReport optimize(PolyMesh& mesh, const ModelFacets* facets, const OptimParams& params,
                     const ProgressFn& progress, std::span<const char> seed_cells,
                     std::span<const CellVerdict> known) {
  if (!seed_cells.empty() && seed_cells.size() != mesh.num_cells())
    throw UsageError("optimize: " + std::to_string(seed_cells.size()) + " seed flags for " +
                     std::to_string(mesh.num_cells()) + " cells");
  OptimReport rep;
  OptimParams resolved = params;
  if (resolved.method == OptimParams::Method::Auto) resolved.method = OptimParams::Method::Local;
  optim_detail::Context ctx(mesh, facets, resolved, seed_cells, known);
  ctx.report = &rep;
  rep.phases = std::move(ctx.setup_phases);
  ctx.progress = &progress;
  // Every run ends with a record() of the final state, so its statistics are
  // the report's "after" (no extra pass over the cells).
  if (resolved.method == OptimParams::Method::Local || resolved.method == OptimParams::Method::Untangle) ctx.init_gates();
  rep.foam_failing_before = rep.foam_failing_after = ctx.foam_failing();
  ctx.record(0);
  rep.before = ctx.last_stats;
  rep.invalid_before = static_cast<int>(rep.iterations.front().invalid);
  if (resolved.method == OptimParams::Method::Local || resolved.method == OptimParams::Method::Untangle)
    optim_detail::run_local(ctx);
  if (resolved.method == OptimParams::Method::Global) optim_detail::run_global(ctx);
  rep.after = ctx.last_stats;
  rep.foam_failing_after = ctx.foam_failing();
  for (std::uint32_t c = 0; c < ctx.foam_ok.size(); ++c)
    if (!ctx.foam_ok[c]) rep.foam_failing_cells.push_back(c);
  optim_detail::list_worst_cells(ctx, rep);
  rep.invalid_after = static_cast<int>(rep.iterations.back().invalid);
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
  j.set("max_quality", max_quality);
  j.set("seconds", seconds);
  j.set("visited", static_cast<unsigned long long>(visited));
  j.set("updates", static_cast<unsigned long long>(updates));
  j.set("full_model", static_cast<unsigned long long>(full_model));
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
  Json ph = Json::object();
  for (const auto& [name, t] : phases) ph.set(name, t);
  j.set("phases", std::move(ph));
  j.set("foam_failing_before", foam_failing_before);
  j.set("foam_failing_after", foam_failing_after);
  Json fc = Json::array();  // the first kMaxWorstCells, for a reader to look at
  for (std::size_t i = 0; i < foam_failing_cells.size() && i < kMaxWorstCells; ++i) fc.push(foam_failing_cells[i]);
  j.set("foam_failing_cells", std::move(fc));
  j.set("cells_above_bound", cells_above_bound);
  Json w = Json::array();
  for (const auto& c : worst_cells) w.push(c.to_json());
  j.set("worst_cells", std::move(w));
  return j;
}

Json WorstCell::to_json() const {
  Json j = Json::object();
  j.set("cell", cell);
  j.set("quality", quality);
  Json p = Json::array();
  for (const auto& [q, m] : pinned) {
    Json e = Json::object();
    e.set("point", q.idx);
    e.set("model_dim", static_cast<int>(m.dim));
    e.set("model_tag", m.tag);
    p.push(std::move(e));
  }
  j.set("pinned", std::move(p));
  j.set("points_on_model_edges", on_edges);
  j.set("points_on_model_faces", on_faces);
  return j;
}


double OptimParams::effective_tol() const {
  if (tol != kMethodTol) return tol;
  const bool fast_local = method != Method::Global && relaxation > 1.0 && polish_sweeps > 0;
  return fast_local ? 2e-2 : 1e-3;
}

void OptimParams::validate() const {
  check_param("OptimParams::max_iter", "iterations", {0, double(kMaxIterLimit)}, max_iter);
  if (tol != kMethodTol) check_param("OptimParams::tol", "relative objective change", {0, kMaxTol}, tol);
  check_param("OptimParams::c", "eq. 3", {kMinDeltaC, kMaxDeltaC}, c);
  check_param("OptimParams::newton_steps", "steps per visit", {1, double(kMaxNewtonSteps)}, newton_steps);
  check_param("OptimParams::settle_move", "relative to cbrt(V0)", {0, kMaxSettleMove}, settle_move);
  check_param("OptimParams::untangle_sweeps", "sweeps", {0, double(kMaxUntangleSweeps)}, untangle_sweeps);
  check_param("OptimParams::max_halvings", "halvings", {0, double(kMaxHalvings)}, max_halvings);
  check_param("OptimParams::polish_sweeps", "sweeps", {0, double(kMaxIterLimit)}, polish_sweeps);
  check_param("OptimParams::polish_share", "share of the range from the mean to the worst quality", {0.0, 1.0}, polish_share);
  check_param("OptimParams::worst_rounds", "rounds", {0, double(kMaxIterLimit)}, worst_rounds);
  check_param("OptimParams::relaxation", "over-relaxation factor", {1.0, kMaxRelaxation}, relaxation);
  check_param("OptimParams::fd_step", "relative to cbrt(V0)", {0, kMaxFdStep, true}, fd_step);
  check_param("OptimParams::global_iterations_per_round", "iterations", {1, double(kMaxIterLimit)},
              global_iterations_per_round);
  check_param("OptimParams::planarity", "weight of the face-flatness term", {0, kMaxPlanarity}, planarity);
  if (planarity > 0 && method != Method::Local && method != Method::Auto && method != Method::None)
    throw UsageError(std::string("OptimParams::planarity: the face-flatness term is in the local scheme only, not in '") +
                     method_name(method) + "' (use --optimize local)");
}

Json OptimParams::to_json() const {
  Json j = Json::object();
  j.set("method", method_name(method));
  j.set("metric", metric == Metric::Q1 ? "q1" : "q2");
  j.set("derivatives", derivatives_name(derivatives));
  j.set("max_iter", max_iter);
  j.set("tol", effective_tol());
  j.set("c", c);
  j.set("newton_steps", newton_steps);
  j.set("settle_move", settle_move);
  j.set("untangle_sweeps", untangle_sweeps);
  j.set("max_halvings", max_halvings);
  j.set("relaxation", relaxation);
  j.set("polish_sweeps", polish_sweeps);
  j.set("polish_share", polish_share);
  j.set("worst_rounds", worst_rounds);
  j.set("fd_step", fd_step);
  j.set("planarity", planarity);
  j.set("keep_boundary", keep_boundary);
  j.set("foam_gate", foam_gate);
  j.set("foam_gate_sweeps", foam_gate_sweeps);
  j.set("foam_repair_untangle", foam_repair_untangle);
  j.set("global_iterations_per_round", global_iterations_per_round);
  return j;
}

OptimParams::Method parse_method(std::string_view s) {
  if (s == "none") return OptimParams::Method::None;
  if (s == "local") return OptimParams::Method::Local;
  if (s == "global") return OptimParams::Method::Global;
  if (s == "untangle") return OptimParams::Method::Untangle;
  if (s == "auto") return OptimParams::Method::Auto;
  throw UsageError("unknown optimisation method '" + std::string(s) + "' (expected auto|none|untangle|local|global)");
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
  if (s == "lagged") return OptimParams::Derivatives::Lagged;
  if (s == "corrected") return OptimParams::Derivatives::Corrected;
  throw UsageError("unknown derivatives '" + std::string(s) + "' (expected analytic|corrected|lagged|fd|exact)");
}

const char* method_name(OptimParams::Method m) {
  switch (m) {
    case OptimParams::Method::None: return "none";
    case OptimParams::Method::Local: return "local";
    case OptimParams::Method::Global: return "global";
    case OptimParams::Method::Untangle: return "untangle";
    case OptimParams::Method::Auto: return "auto";
  }
  return "none";
}
const char* derivatives_name(OptimParams::Derivatives d) {
  switch (d) {
    case OptimParams::Derivatives::Exact: return "exact";
    case OptimParams::Derivatives::Analytic: return "analytic";
    case OptimParams::Derivatives::Lagged: return "lagged";
    case OptimParams::Derivatives::Corrected: return "corrected";
    case OptimParams::Derivatives::FiniteDifference: return "fd";
  }
  return "fd";
}

}  // namespace polydual
