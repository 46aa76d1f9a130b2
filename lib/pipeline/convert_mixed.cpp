#include "pipeline/convert_mixed.h"

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "classify/classify_primal.h"
#include "classify/primal_features.h"
#include "dual/cleanup.h"
#include "dual/primal_dual.h"
#include "mesh/cell_soup.h"
#include "mesh/model_facets.h"
#include "optim/foam_gate.h"
#include "pipeline/run_stage.h"
#include "quality/primal_reference.h"
#include "split/mixed_split.h"

namespace polydual::pipeline_detail {

namespace {

// The names of the soup's physical groups by region and model face tag: the
// first named group (in (dim, tag) order) listing the tag, as classify()
// names its model entities.
ModelNames group_names(const TetSoup& soup) {
  ModelNames n;
  for (const NamedGroup& g : soup.groups) {
    if (g.name.empty() || (g.dim != 3 && g.dim != 2)) continue;
    for (std::int32_t tag : g.entities) (g.dim == 3 ? n.regions : n.faces).emplace(tag, g.name);
  }
  return n;
}

Json primal_stats(const MixedPrimal& p) {
  Json j = Json::object();
  Json cells = Json::object();
  for (int t = 0; t < kNumCellTypes; ++t)
    if (p.cell_counts[t]) cells.set(std::string(descriptor(CellType(t)).plural), p.cell_counts[t]);
  j.set("cells", cells);
  j.set("vertices", p.mesh.num_vertices());
  j.set("faces", p.mesh.num_faces());
  j.set("edges", p.mesh.num_edges());
  return j;
}

// build_primal, then again with the inferred model faces split at their
// feature edges (classify/primal_features.h) when there are any.
MixedPrimal classify_mixed(const TetSoup& soup, const ClassifyParams& params, std::vector<std::string>& warnings) {
  MixedPrimal p;
  p.cell_counts = mixed_cell_counts(soup);
  if (soup.tets.empty() && soup.other_cells.empty())
    throw InputError(soup.source, "",
                     "a surface mesh (" + describe_cell_counts(p.cell_counts) +
                         "): convert makes the dual of volume meshes only (`polydual info` checks and counts its cells)");
  CellSoup cells = cell_soup(soup);
  p.mesh = build_primal(cells, &warnings);
  if (tag_inferred_model_faces(cells, p.mesh, params.feature_angle_deg) > 0) p.mesh = build_primal(std::move(cells));
  p.names = group_names(soup);
  p.reference = primal_reference(p.mesh);
  return p;
}

PolyMesh mixed_dual_stages(ConvertResult& r, const PipelineParams& params, const ConvertHooks& hooks) {
  const PrimalMesh& m = r.mixed->mesh;
  DualStats dual_stats;
  DualDraft draft = run_stage(r.report, hooks, "dual", [&](Json& stats) {
    DualDraft d = build_primal_dual_draft(m, params.dual, &dual_stats);
    stats = dual_stats.to_json();
    return d;
  });
  run_stage(r.report, hooks, "cleanup", [&](Json& stats) {
    stats = cleanup_dual(draft).to_json();
    return 0;
  });
  return run_stage(r.report, hooks, "cells", [&](Json& stats) {
    PolyMesh pm = assemble_cells(std::move(draft));
    require_finite_points(pm, m.source());
    stats = Json::object();
    stats.set("cells", pm.num_cells());
    return pm;
  });
}

CheckResult check_mixed(const ConvertResult& r, bool with_validation) {
  return check_mesh(r.mesh, r.mixed->reference, with_validation);
}

// The optimiser's parameters on a mixed mesh: Auto untangles only, since the
// kappa objective would make the layers of prisms and hexahedra isotropic
// (OptimParams::Method::Auto).
OptimParams mixed_optim_params(const PipelineParams& params) {
  OptimParams optim = params.optim;
  if (optim.method == OptimParams::Method::Auto) optim.method = OptimParams::Method::Untangle;
  return optim;
}

// The mixed split (split/mixed_split.h) after the first optimised dual: the
// optimiser reaches it as a callback with the mixed method; a mesh it changed
// is then validated (check_split), as the tet pipeline does.
void split_mixed(ConvertResult& r, const PipelineParams& params, const ConvertHooks& hooks) {
  const ModelFacets facets = model_facets(r.mixed->mesh);
  const OptimParams optim = mixed_optim_params(params);
  SplitHooks split_hooks;
  split_hooks.progress = hooks.progress;
  split_hooks.metric = params.optim.metric;
  split_hooks.optimise = [&](PolyMesh& mesh, std::span<const char> seed, std::span<const CellVerdict> verdicts, bool) {
    return optimize(mesh, &facets, optim, hooks.progress, seed, verdicts).to_json();
  };
  if (optim.foam_gate) split_hooks.foam_failing = [](const PolyMesh& mesh) { return foam_check(mesh).cells; };
  const int rounds = run_stage(r.report, hooks, "split", [&](Json& stats) {
    MixedSplitRun run = run_mixed_split(r.mixed->mesh, params.dual, params.split, r.mesh, r.check, split_hooks);
    stats = std::move(run.stats);
    return run.rounds;
  });
  if (rounds == 0) return;  // the mesh is check_after's, validated there
  r.check = run_stage(r.report, hooks, "check_split", [&](Json& stats) {
    CheckResult c = check_mixed(r, true);
    stats = c.to_json();
    stats.set("invalid_after", c.invalid_cells);
    return c;
  });
}

}  // namespace

ModelRef mixed_vertex_class(const PrimalMesh& m, std::uint64_t in) {
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (m.input_vertex(VertexId(v)) == in) return m.vertex_class(VertexId(v));
  return ModelRef{};
}

void run_mixed_stages(ConvertResult& r, const TetSoup& soup, const PipelineParams& params, const ConvertHooks& hooks) {
  ConvertReport& rep = r.report;
  r.mixed = run_stage(rep, hooks, "classify", [&](Json& stats) {
    MixedPrimal p = classify_mixed(soup, params.classify, r.warnings);
    stats = primal_stats(p);
    return p;
  });
  // The tet optimisation (on by default) moves tets only: recorded as skipped.
  if (params.tetopt.enabled)
    run_stage(rep, hooks, "optimize_tets", [&](Json& stats) {
      stats = Json::object();
      stats.set("skipped", "the tet optimisation works on tet meshes only");
      return 0;
    });
  r.mesh = mixed_dual_stages(r, params, hooks);
  const bool optimise = params.optim.method != OptimParams::Method::None;
  r.check = run_stage(rep, hooks, "check", [&](Json& stats) {
    CheckResult c = check_mixed(r, !optimise);
    stats = c.to_json();
    return c;
  });
  rep.invalid_before = r.check.invalid_cells;
  if (optimise) {
    run_stage(rep, hooks, "optimize", [&](Json& stats) {
      const ModelFacets facets = model_facets(r.mixed->mesh);
      stats = optimize(r.mesh, &facets, mixed_optim_params(params), hooks.progress, {}, r.check.verdicts).to_json();
      return 0;
    });
    r.check = run_stage(rep, hooks, "check_after", [&](Json& stats) {
      CheckResult c = check_mixed(r, true);
      stats = c.to_json();
      return c;
    });
  }
  if (params.split.enabled && optimise) split_mixed(r, params, hooks);
}

}  // namespace polydual::pipeline_detail
