#include "pipeline/convert.h"

#include <algorithm>
#include <cstdio>
#include <new>
#include <stdexcept>

#include <sys/resource.h>

#include <tbb/parallel_invoke.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/stopwatch.h"
#include "io/output_guard.h"
#include "io/format_registry.h"
#include "io/read_tet_mesh.h"
#include "classify/self_overlap.h"
#include "optim/foam_gate.h"
#include "pipeline/convert_mixed.h"
#include "pipeline/run_stage.h"
#include "split/split.h"

namespace polydual {

namespace {
using pipeline_detail::require_finite_points;
using pipeline_detail::run_stage;

// Algorithm 1 as three stages (design §4): the draft (steps 1-7 and the
// cleanup's hints), the cleanup (§2.8), the cells (step 8); cuts may be null.
PolyMesh run_dual_stages(ConvertResult& r, const PipelineParams& params, const ConvertHooks& hooks,
                         const VertexCuts* cuts) {
  DualStats dual_stats;
  DualDraft draft = run_stage(r.report, hooks, "dual", [&](Json& stats) {
    DualDraft d = build_dual_draft(r.primal, params.dual, &dual_stats, cuts);
    stats = dual_stats.to_json();
    return d;
  });
  run_stage(r.report, hooks, "cleanup", [&](Json& stats) {
    stats = cleanup_dual(draft).to_json();
    return 0;
  });
  return run_stage(r.report, hooks, "cells", [&](Json& stats) {
    PolyMesh pm = assemble_cells(std::move(draft));
    require_finite_points(pm, r.primal.source());
    stats = Json::object();
    stats.set("cells", pm.num_cells());
    return pm;
  });
}

// Whether the tets of m cover some place twice (classify/self_overlap.h).
bool overlaps(const ClassifiedTetMesh& m, std::string* why) {
  try {
    check_self_overlap(m);
    return false;
  } catch (const InputError& e) {
    *why = e.what();
    return true;
  }
}

// The tet optimisation (optim/tet_optimize.h). Every tet stays positive,
// but vertices sliding on curved model faces can fold the boundary over
// another part of it (a notched random mesh: two boundary triangles crossing,
// proofs/tet_optimize.md T5): the result is checked as the input was, and
// on an overlap the optimisation runs again with boundary vertices moving
// only where the model is flat, which keeps the boundary's point set (T4).
ClassifiedTetMesh optimise_tets(const ClassifiedTetMesh& primal, const TetOptParams& params, Json& stats) {
  TetOptReport report;
  ClassifiedTetMesh moved = optimize_tets(primal, params, &report);
  std::string why;
  if (params.move_curved && overlaps(moved, &why)) {
    TetOptParams flat = params;
    flat.move_curved = false;
    moved = optimize_tets(primal, flat, &report);
    stats = report.to_json();
    stats.set("curved_moves_undone", why);
    return moved;
  }
  stats = report.to_json();
  return moved;
}

// Interior vertices that the tet stage inserted (optim/steiner.h) each make
// a cell: the dual is then not that of the mesh given, which the user is told.
void warn_inserted_points(ConvertResult& r, std::size_t vertices_before) {
  const std::size_t n = r.primal.num_vertices() - vertices_before;
  if (n == 0) return;
  char share[32];
  std::snprintf(share, sizeof share, "%.1f %%", 100.0 * double(n) / double(vertices_before));
  r.warnings.push_back("inserted " + std::to_string(n) + " interior vertices (" + share + " of the mesh's " +
                       std::to_string(vertices_before) +
                       ") into tets that span the solid, each the vertex of a cell of the dual; "
                       "--interior-points off keeps the mesh's vertices");
}

// The paper's caps join the centres of the boundary triangles round a
// boundary vertex and so cut every convex corner of a curved model face:
// small curved materials lose volume (a Gmsh inclusion of a thousand tets
// about half of it). A material whose dual is more than 1 % smaller than
// its tets is named in a warning; the keep mode's volume is exact
// (proofs/dual_invariants.md L5b).
void warn_lost_volume(ConvertResult& r) {
  const ValidationReport& v = r.check.validation;
  std::string lost;
  std::size_t n = 0;
  for (const auto& [tag, primal] : v.primal_material_volume) {
    const auto it = v.material_volume.find(tag);
    if (it == v.material_volume.end() || !(primal > 0) || it->second >= 0.99 * primal) continue;
    if (n++ < 6) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%smaterial %d %.1f %%", lost.empty() ? "" : ", ", int(tag),
                    100.0 * (primal - it->second) / primal);
      lost += buf;
    }
  }
  if (n == 0) return;
  if (n > 6) lost += " and " + std::to_string(n - 6) + " more";
  r.warnings.push_back("the dual is smaller than the mesh in " + std::to_string(n) +
                       (n == 1 ? " material (" : " materials (") + lost +
                       "): the paper's caps cut the corners of curved model faces; --boundary keep keeps "
                       "every material's volume exactly");
}

// The split stage (split/split.h) after the first dual, its optimisation
// and check: the optimiser reaches the split as a callback (the rounds
// untangle only; the mesh kept gets the chosen method, near its cuts unless
// the method is global). facets: model_facets(r.primal) when there is an optimiser.
void run_split_stage(ConvertResult& r, SplitState& st, const ModelFacets& facets, const PipelineParams& params,
                     const ConvertHooks& hooks) {
  SplitHooks split_hooks;
  split_hooks.progress = hooks.progress;
  split_hooks.metric = params.optim.metric;
  if (params.optim.method != OptimParams::Method::None)
    split_hooks.optimise = [&](PolyMesh& mesh, std::span<const char> seed, std::span<const CellVerdict> verdicts,
                               bool untangle_only) {
      if (untangle_only) {
        OptimParams untangle = params.optim;
        untangle.method = OptimParams::Method::Untangle;
        untangle.foam_repair_untangle = false;  // the rounds' result only decides their cuts
        return optimize(mesh, &facets, untangle, {}, seed, verdicts).to_json();
      }
      const bool local = params.optim.method != OptimParams::Method::Global;
      return optimize(mesh, &facets, params.optim, hooks.progress, local ? seed : std::span<const char>(), verdicts)
          .to_json();
    };
  if (params.optim.method != OptimParams::Method::None && params.optim.foam_gate) {
    split_hooks.foam_failing = [](const PolyMesh& mesh) { return foam_check(mesh).cells; };
    split_hooks.optimise_foam_gated = [&](PolyMesh& mesh, std::span<const char> seed,
                                          std::span<const CellVerdict> verdicts, bool) {
      OptimParams gated = params.optim;
      gated.foam_gate_sweeps = true;
      if (gated.method == OptimParams::Method::Global) gated.method = OptimParams::Method::Local;
      return optimize(mesh, &facets, gated, {}, seed, verdicts).to_json();
    };
  }
  run_stage(r.report, hooks, "split", [&](Json& stats) {
    stats = run_split(r.primal, params.dual, params.split, st, r.mesh, r.check, split_hooks);
    return 0;
  });
  // r.check holds the verdicts of r.mesh as it is (the kept round's, or those
  // after the re-optimisation): only the validation is still to run.
  r.check = run_stage(r.report, hooks, "check_split", [&](Json& stats) {
    CheckResult c = check_with_known_verdicts(r.mesh, &r.primal, std::move(r.check));
    stats = c.to_json();
    stats.set("invalid_after", c.invalid_cells);
    return c;
  });
}

// "cell C (vertex V, class dim D tag T)" of each invalid cell, V in the
// input numbering; at most `limit` items.
std::vector<std::string> invalid_cell_items(const ConvertResult& r, std::size_t limit) {
  std::vector<std::string> items;
  const std::vector<VertexId> internal = internal_of_input(r.primal);
  for (std::size_t c = 0; c < r.check.verdicts.size() && items.size() < limit; ++c) {
    if (r.check.verdicts[c].valid) continue;
    const VertexId in = r.mesh.cell_primal[c];
    const ModelRef cls = r.mixed ? pipeline_detail::mixed_vertex_class(r.mixed->mesh, in.idx)
                         : in.idx < internal.size() && internal[in.idx].valid() ? r.primal.vertex_class(internal[in.idx])
                                                                                : ModelRef{};
    items.push_back("cell " + std::to_string(c) + " (vertex " + std::to_string(in.idx) + ", class dim " +
                    std::to_string(cls.dim) + " tag " + std::to_string(cls.tag) + ")");
  }
  return items;
}

// --require-valid: the validation's failed checks (ValidationReport::defects)
// and every cell still invalid, with its primal vertex (input numbering) and
// its classification, as one InputError.
void require_valid(const ConvertResult& r) {
  const std::vector<Defect> defects = r.check.validation.defects();
  if (r.check.invalid_cells == 0 && defects.empty()) return;
  const std::string& source = r.mixed ? r.mixed->mesh.source() : r.primal.source();
  std::string what;
  if (!defects.empty()) what = "the dual is not sound: " + defects_sentence(defects) + (r.check.invalid_cells ? "; " : "");
  if (r.check.invalid_cells == 0) throw InputError(source, "", what);
  what += std::to_string(r.check.invalid_cells) + " cells remain invalid after the split:";
  for (const std::string& item : invalid_cell_items(r, r.check.invalid_cells)) what += " " + item + ";";
  throw InputError(source, "", what);
}

// What follows the last check on either path: the lost-volume warning, the
// final count, --require-valid.
// OpenFOAM's own verdict on the mesh returned (optim/foam_gate.h's
// foam_check, what checkMesh -allGeometry computes in floating point: face
// pyramids and face tets), a stage of the report and, when faces fail, a
// warning naming their cells.
void openfoam_check(ConvertResult& r, const ConvertHooks& hooks) {
  const FoamCheck fc = run_stage(r.report, hooks, "openfoam_check", [&](Json& stats) {
    FoamCheck c = foam_check(r.mesh);
    stats = c.to_json();
    return c;
  });
  if (fc.cells.empty()) return;
  std::string cells;
  for (std::size_t i = 0; i < fc.cells.size() && i < kListedDefects; ++i)
    cells += (i ? ", " : "") + std::to_string(fc.cells[i]);
  if (fc.cells.size() > kListedDefects) cells += ", ...";
  r.warnings.push_back("OpenFOAM's checkMesh will find " + std::to_string(fc.pyramid_faces) +
                       " faces with wrongly oriented pyramids and " + std::to_string(fc.face_tet_faces) +
                       " with face-tet errors (its floating-point centres; the exact test passes them), in cells " +
                       cells);
}

void finish_pipeline(ConvertResult& r, const PipelineParams& params, const ConvertHooks& hooks) {
  openfoam_check(r, hooks);
  if (params.dual.boundary == BoundaryMode::Caps) warn_lost_volume(r);
  r.report.invalid_after = r.check.invalid_cells;
  if (params.split.require_valid) require_valid(r);
}

// The stages from classify to the final check, appended to r.report. A soup
// the caller owns (`release`, may be null) is freed once classified: it is
// not needed after, and the split rounds are the memory peak.
void run_pipeline(ConvertResult& r, const TetSoup& soup, const PipelineParams& params, const ConvertHooks& hooks,
                  TetSoup* release = nullptr) {
  ConvertReport& rep = r.report;
  r.ignored = soup.ignored;
  r.warnings = soup.warnings;
  if (is_mixed_or_surface(soup)) {  // design §14: the primal of any cell type
    pipeline_detail::run_mixed_stages(r, soup, params, hooks);
    if (release) *release = TetSoup{};
    finish_pipeline(r, params, hooks);
    return;
  }
  r.primal = run_stage(rep, hooks, "classify", [&](Json& stats) {
    ClassifyStats st;
    ClassifiedTetMesh m = classify(soup, params.classify, &st);
    stats = st.to_json();
    return m;
  });
  r.input_tets = r.primal.num_tets();
  if (release) *release = TetSoup{};
  if (params.tetopt.enabled) {
    const std::size_t vertices = r.primal.num_vertices();
    TetOptParams tetopt = params.tetopt;
    if (params.optim.method == OptimParams::Method::None) tetopt.steiner.ratio = tetopt.steiner.ratio_without_optimiser;
    r.primal = run_stage(rep, hooks, "optimize_tets", [&](Json& stats) { return optimise_tets(r.primal, tetopt, stats); });
    warn_inserted_points(r, vertices);
  }
  // What the classification completed (an incomplete given classification).
  for (const std::string& w : r.primal.classification_warnings()) r.warnings.push_back(w);
  SplitState st;
  if (params.split.enabled) {
    st = run_stage(rep, hooks, "cuts", [&](Json& stats) {
      SplitState s = begin_split(r.primal);
      stats = Json::object();
      stats.set("free_edge_vertices", s.free_edge.num_vertices_cut());
      return s;
    });
  }
  r.mesh = run_dual_stages(r, params, hooks, st.free_edge.empty() ? nullptr : &st.free_edge);
  const bool optimise = params.optim.method != OptimParams::Method::None;
  // Validation is topological and the optimiser moves points only: it runs
  // once, on the mesh that is returned (with the split, by check_split).
  r.check = run_stage(rep, hooks, "check", [&](Json& stats) {
    CheckResult c = check_mesh(r.mesh, &r.primal, !optimise && !params.split.enabled);
    stats = c.to_json();
    return c;
  });
  rep.invalid_before = r.check.invalid_cells;
  ModelFacets facets;  // what the optimiser reads of the primal, made once
  if (optimise) {
    run_stage(rep, hooks, "optimize", [&](Json& stats) {
      facets = model_facets(r.primal);
      stats = optimize(r.mesh, &facets, params.optim, hooks.progress, {}, r.check.verdicts).to_json();
      return 0;
    });
    // With the split, check_split validates the mesh that is returned.
    r.check = run_stage(rep, hooks, "check_after", [&](Json& stats) {
      CheckResult c = check_mesh(r.mesh, &r.primal, !params.split.enabled);
      stats = c.to_json();
      return c;
    });
  }
  if (params.split.enabled) run_split_stage(r, st, facets, params, hooks);
  finish_pipeline(r, params, hooks);
}

}  // namespace

Defect invalid_cells_defect(const ConvertResult& r) {
  return Defect{"invalid_cells", "cells not star-shaped by the exact test", r.check.invalid_cells,
                invalid_cell_items(r, kListedDefects)};
}

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
  std::vector<CellField> fields = verdict_fields(r.check.verdicts);
  // A split mesh: each cell's uncut cell ("split_from", PolyMesh::cell_origin),
  // so that a viewer can show which cells were split and into what.
  if (!r.mesh.cell_origin.empty()) {
    std::vector<std::int32_t> from(r.mesh.cell_origin.size());
    for (std::size_t c = 0; c < from.size(); ++c)
      from[c] = r.mesh.cell_origin[c].valid() ? std::int32_t(r.mesh.cell_origin[c].idx) : -1;
    fields.push_back(CellField{"split_from", std::move(from)});
  }
  ModelNames names = r.mixed ? r.mixed->names : model_names(r.primal.model());
  return write_poly_mesh(r.mesh, path, format, WriteContext{options, std::move(fields), std::move(names)});
}

ConvertResult convert_file(const std::string& in, const std::string& out, PolyFormat format,
                           const PipelineParams& params, const ConvertHooks& hooks, const PolyWriteOptions& options) {
  params.validate();
  const std::string inputs[] = {in};
  check_output_target(inputs, out, format.writer().output_kind(), options.foam.force,
                      std::string(format.writer().extension()));
  const Stopwatch clock;
  ConvertResult r;
  TetSoup soup = run_stage(r.report, hooks, "read", [&](Json& stats) {
    TetSoup s = read_tet_mesh(in);
    stats = Json::object();
    stats.set("path", in);
    return s;
  });
  run_pipeline(r, soup, params, hooks, &soup);
  // The writer is serial: the summary's face flatness (a statistic, not a
  // decision; deterministic for any thread count) is measured meanwhile. An
  // exception in either waits for the other, then propagates.
  FlatnessStats flat;
  tbb::parallel_invoke(
      [&] {
        r.written = run_stage(r.report, hooks, "write", [&](Json& stats) {
          Json w = write_result(r, out, format, options);
          stats = w;
          return w;
        });
      },
      [&] { flat = flatness_stats(r.mesh); });
  r.flatness = flat;
  r.report.seconds = clock.seconds();
  return r;
}

OptimizeResult optimize_mesh(PolyMesh& mesh, const ClassifiedTetMesh* primal, const OptimParams& params,
                             const ProgressFn& progress) {
  params.validate();
  OptimizeResult r;
  ModelFacets facets;
  if (primal) facets = model_facets(*primal);
  r.optim = optimize(mesh, primal ? &facets : nullptr, params, progress);
  r.check = check_mesh(mesh, primal);
  return r;
}

}  // namespace polydual
