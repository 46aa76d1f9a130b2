#include "pipeline/convert.h"

#include "core/interrupt.h"
#include "core/stopwatch.h"
#include "io/output_guard.h"
#include "io/read_tet_mesh.h"
#include "split/split.h"

namespace polydual {

namespace {
// Runs one stage, times it and records it; returns the stage's value. A
// pending interrupt (Ctrl-C, SIGTERM) stops the pipeline between stages.
template <class F>
auto run_stage(ConvertReport& report, const ConvertHooks& hooks, const char* name, F&& stage) {
  throw_if_interrupted();
  const Stopwatch clock;
  Json stats;
  auto value = stage(stats);
  report.stages.push_back(StageRecord{name, clock.seconds(), std::move(stats)});
  if (hooks.stage_done) hooks.stage_done(report.stages.back());
  return value;
}


// The split stage (split/split.h) on every cell still invalid, with the counts
// by cause (class of the primal vertex, slit cell), then the check again.
void run_split(ConvertResult& r, const SplitParams& params, const ConvertHooks& hooks) {
  run_stage(r.report, hooks, "split", [&](Json& stats) {
    constexpr const char* kClass[4] = {"model_vertex", "model_edge", "model_face", "interior"};
    std::vector<CellId> cells;
    std::size_t by_class[4] = {0, 0, 0, 0}, slit = 0;
    for (std::size_t c = 0; c < r.check.verdicts.size(); ++c) {
      if (r.check.verdicts[c].valid) continue;
      cells.push_back(CellId(c));
      const int dim = r.primal.vertex_class(r.mesh.cell_primal[c]).dim;
      ++by_class[dim >= 0 && dim <= 3 ? dim : 3];
      bool is_slit = false;
      for (HalfFace h : r.mesh.cell(CellId(c)))
        is_slit |= r.mesh.face_owner[h.face().idx] == r.mesh.face_neighbour[h.face().idx];
      slit += is_slit;
    }
    stats = split_cells(r.mesh, cells, params).to_json();
    Json by = Json::object();
    for (int k = 0; k < 4; ++k) by.set(kClass[k], by_class[k]);
    stats.set("invalid_by_class", by);
    stats.set("slit_cells", slit);
    return 0;
  });
  r.check = run_stage(r.report, hooks, "check_split", [&](Json& stats) {
    CheckResult c = check_mesh(r.mesh, &r.primal);
    stats = c.to_json();
    stats.set("invalid_after", c.invalid_cells);
    return c;
  });
}

// The stages from classify to the final check, appended to r.report.
void run_pipeline(ConvertResult& r, const TetSoup& soup, const PipelineParams& params, const ConvertHooks& hooks) {
  ConvertReport& rep = r.report;
  r.ignored = soup.ignored;
  r.warnings = soup.warnings;
  r.primal = run_stage(rep, hooks, "classify", [&](Json& stats) {
    ClassifyStats st;
    ClassifiedTetMesh m = classify(soup, params.classify, &st);
    stats = st.to_json();
    return m;
  });
  if (params.tetopt.enabled)
    run_stage(rep, hooks, "optimize_tets", [&](Json& stats) { stats = optimize_tets(r.primal, params.tetopt).to_json(); return 0; });
  // What the classification completed (an incomplete given classification).
  for (const std::string& w : r.primal.classification_warnings()) r.warnings.push_back(w);
  // Algorithm 1 as three stages (design §4): the draft (steps 1-7 and the
  // cleanup's hints), the cleanup (§2.8), the cells (step 8).
  DualStats dual_stats;
  DualDraft draft = run_stage(rep, hooks, "dual", [&](Json& stats) {
    DualDraft d = build_dual_draft(r.primal, params.dual, &dual_stats);
    stats = dual_stats.to_json();
    return d;
  });
  run_stage(rep, hooks, "cleanup", [&](Json& stats) {
    stats = cleanup_dual(draft).to_json();
    return 0;
  });
  r.mesh = run_stage(rep, hooks, "cells", [&](Json& stats) {
    PolyMesh pm = assemble_cells(std::move(draft));
    stats = Json::object();
    stats.set("cells", pm.num_cells());
    return pm;
  });
  const bool optimise = params.optim.method != OptimParams::Method::None;
  // Validation is topological and the optimiser moves points only: it runs
  // once, on the mesh that is returned.
  r.check = run_stage(rep, hooks, "check", [&](Json& stats) {
    CheckResult c = check_mesh(r.mesh, &r.primal, !optimise);
    stats = c.to_json();
    return c;
  });
  rep.invalid_before = r.check.invalid_cells;
  if (optimise) {
    run_stage(rep, hooks, "optimize", [&](Json& stats) {
      stats = optimize(r.mesh, &r.primal, params.optim, hooks.progress).to_json();
      return 0;
    });
    r.check = run_stage(rep, hooks, "check_after", [&](Json& stats) {
      CheckResult c = check_mesh(r.mesh, &r.primal);
      stats = c.to_json();
      return c;
    });
  }
  if (params.split.enabled && r.check.invalid_cells > 0) run_split(r, params.split, hooks);
  rep.invalid_after = r.check.invalid_cells;
}

}  // namespace

const StageRecord* ConvertReport::stage(const std::string& name) const {
  for (const StageRecord& s : stages)
    if (s.name == name) return &s;
  return nullptr;
}

ConvertResult convert(const TetSoup& soup, const PipelineParams& params, const ConvertHooks& hooks) {
  params.validate();
  const Stopwatch clock;
  ConvertResult r;
  run_pipeline(r, soup, params, hooks);
  r.report.seconds = clock.seconds();
  return r;
}

Json write_result(const ConvertResult& r, const std::string& path, PolyFormat format,
                  const PolyWriteOptions& options) {
  return write_poly_mesh(r.mesh, path, format, verdict_fields(r.check.verdicts), options);
}

ConvertResult convert_file(const std::string& in, const std::string& out, PolyFormat format,
                           const PipelineParams& params, const ConvertHooks& hooks, const PolyWriteOptions& options) {
  params.validate();
  const std::string inputs[] = {in};
  check_output_target(inputs, out, format == PolyFormat::Foam ? OutputKind::FoamCase : OutputKind::File,
                      options.foam.force, format == PolyFormat::Vtu ? ".vtu" : "");
  const Stopwatch clock;
  ConvertResult r;
  const TetSoup soup = run_stage(r.report, hooks, "read", [&](Json& stats) {
    TetSoup s = read_tet_mesh(in);
    stats = Json::object();
    stats.set("path", in);
    return s;
  });
  run_pipeline(r, soup, params, hooks);
  r.written = run_stage(r.report, hooks, "write", [&](Json& stats) {
    Json w = write_result(r, out, format, options);
    stats = w;
    return w;
  });
  r.report.seconds = clock.seconds();
  return r;
}

OptimizeResult optimize_mesh(PolyMesh& mesh, const ClassifiedTetMesh* primal, const OptimParams& params,
                             const ProgressFn& progress) {
  params.validate();
  OptimizeResult r;
  r.optim = optimize(mesh, primal, params, progress);
  r.check = check_mesh(mesh, primal);
  return r;
}

}  // namespace polydual
