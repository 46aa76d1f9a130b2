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
#include "dual/cut_topology.h"
#include "io/output_guard.h"
#include "io/format_registry.h"
#include "io/read_tet_mesh.h"
#include "quality/metrics.h"
#include "quality/stencil.h"
#include "split/coarsen.h"
#include "split/cuts.h"
#include "split/local_round.h"
#include "split/recheck.h"
#include "split/split.h"
#include "split/warm_start.h"

namespace polydual {

namespace {
// The process's peak resident set so far, MB (Linux: ru_maxrss in KiB).
double peak_rss_mb() {
  rusage u{};
  return getrusage(RUSAGE_SELF, &u) == 0 ? double(u.ru_maxrss) / 1024.0 : 0.0;
}

// Runs one stage, times it and records it; returns the stage's value. A
// pending interrupt (Ctrl-C, SIGTERM) stops the pipeline between stages.
template <class F>
auto run_stage(ConvertReport& report, const ConvertHooks& hooks, const char* name, F&& stage) {
  throw_if_interrupted();
  const Stopwatch clock;
  Json stats;
  auto value = [&] {
    try {
      return stage(stats);
    } catch (const std::bad_alloc&) {
      throw OutOfMemory(name, peak_rss_mb());
    }
  }();
  report.stages.push_back(StageRecord{name, clock.seconds(), std::move(stats), peak_rss_mb()});
  if (hooks.stage_done) hooks.stage_done(report.stages.back());
  return value;
}


// The dual's points are computed in floating point (means, normals); a mesh
// whose scale the input check let through but whose arithmetic still over- or
// underflowed is refused here, before the optimiser sees a NaN.
void require_finite_points(const PolyMesh& pm, const std::string& source) {
  for (std::size_t p = 0; p < pm.num_points(); ++p)
    if (!is_finite(pm.points[p]))
      throw InputError(source, "dual point " + std::to_string(p + 1),
                       "not finite: the mesh's coordinates are out of the range double arithmetic handles "
                       "(rescale the mesh)");
}

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

// Internal vertex id of each input vertex id (invalid: a dropped input point).
std::vector<VertexId> internal_of_input(const ClassifiedTetMesh& m) {
  std::uint32_t n = 0;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) n = std::max(n, m.input_vertex(VertexId(v)) + 1);
  std::vector<VertexId> out(n, VertexId::invalid());
  for (std::size_t v = 0; v < m.num_vertices(); ++v) out[m.input_vertex(VertexId(v))] = VertexId(v);
  return out;
}

// State of the split loop (split/split.h): per primal vertex (internal
// numbering) whether it is cut whole (the fallback, one cell per tet) and the
// cause it was first cut for.
struct SplitState {
  VertexCuts free_edge, cuts;  // cuts: the union used by the current dual
  std::vector<char> whole;
  std::vector<CutCause> cause;
  std::vector<VertexId> internal_of_input;  // cell_primal (input numbering) -> internal
};

std::size_t num_whole(const SplitState& st) { return std::size_t(std::count(st.whole.begin(), st.whole.end(), char(1))); }

// A split round's progress (the command shows it when the stage runs long).
void split_progress(const ConvertHooks& hooks, const PipelineParams& params, const Stopwatch& clock, int round,
                    std::size_t invalid, const SplitState& st) {
  if (!hooks.progress) return;
  char detail[128];
  std::snprintf(detail, sizeof detail, "invalid cells %zu, vertices cut whole %zu", invalid,
                num_whole(st));
  hooks.progress(ProgressEvent{"split", round, params.split.max_rounds, clock.seconds(), detail});
}

// The union of the free-edge cuts and the whole cuts of the marked vertices.
VertexCuts union_of_cuts(const SplitState& st, const ClassifiedTetMesh& m) {
  return with_whole_cuts(m, st.free_edge, st.whole);
}

// The cells holding a point pinned by a whole-cut vertex (dual/cut_topology.h):
// where the split changed the optimised mesh, the seed of its re-optimisation.
std::vector<char> split_region(const ClassifiedTetMesh& m, const VertexCuts& cuts, const PolyMesh& mesh) {
  std::vector<char> pin(mesh.num_points(), 0), seed(mesh.num_cells(), 0);
  if (mesh.point_origin.size() != mesh.num_points()) return std::vector<char>(mesh.num_cells(), 1);
  for (std::size_t p = 0; p < pin.size(); ++p) pin[p] = char(pinned(m, &cuts, mesh.point_origin[p]));
  CellPointScan points(mesh);
  for (std::size_t c = 0; c < seed.size(); ++c)
    for (PointId p : points(CellId(c)))
      if (pin[p.idx]) {
        seed[c] = 1;
        break;
      }
  return seed;
}

// The cells holding a point pinned by one of `raised` (vertices newly cut
// whole: their barycentric points are where the previous positions were
// lost) or found invalid by `check`: the seeds of a round's re-optimisation.
std::vector<char> round_seed(const ClassifiedTetMesh& m, std::span<const VertexId> raised, const PolyMesh& mesh,
                             const CheckResult& check) {
  VertexCuts newly;
  newly.whole.assign(m.num_vertices(), 0);
  for (VertexId v : raised) newly.whole[v.idx] = 1;
  std::vector<char> seed = split_region(m, newly, mesh);
  for (std::size_t c = 0; c < seed.size() && c < check.verdicts.size(); ++c) seed[c] |= char(!check.verdicts[c].valid);
  return seed;
}

// One round: rebuild with the union of cuts, the points not pinned by a whole
// vertex warm-started from `old` (the previous mesh), check (verdicts only;
// the cells equal to one of `old` keep their verdict in old_check,
// split/recheck.h). With `reoptimise` (the optimised rounds) and cells still
// invalid, the optimiser then runs near the newly pinned points and the
// invalid cells, and the mesh is checked again: a neighbour that the
// barycentric points of `raised` made invalid is moved back to validity
// rather than cut whole in the next round (the optimiser accepts no move that
// makes a valid cell invalid, exactly). Leaves the new mesh and its check in
// r; returns the round's record.
Json split_round(ConvertResult& r, const PolyMesh& old, const CheckResult& old_check, SplitState& st,
                 const PipelineParams& params, std::span<const VertexId> raised, bool reoptimise) {
  Json sec = Json::object();  // the round's parts, wall seconds
  Stopwatch w;
  auto lap = [&](const char* part) {
    sec.set(part, w.seconds());
    w = Stopwatch();
  };
  st.cuts = union_of_cuts(st, r.primal);
  lap("cuts");
  DualStats ds;
  PolyMesh fresh = build_dual(r.primal, params.dual, &ds, &st.cuts);
  lap("dual");
  sec.set("dual_parts", ds.to_json());
  Json j = Json::object();
  j.set("local", false);
  j.set("closure", !reoptimise);
  j.set("vertices_whole", num_whole(st));
  j.set("cells", fresh.num_cells());
  std::vector<PointId> from_old;
  j.set("points_warm_started", warm_start(fresh, old, r.primal, st.cuts, &from_old));
  lap("warm_start");
  RecheckStats rs;
  r.check = recheck_mesh(fresh, old, old_check, from_old, &rs);
  lap("star_test");
  r.mesh = std::move(fresh);
  j.set("invalid_built", r.check.invalid_cells);
  if (reoptimise && r.check.invalid_cells > 0) {
    // Untangling only: validity is what decides the next round's cuts; the
    // kept mesh is smoothed once at the end (run_split).
    const std::vector<char> seed = round_seed(r.primal, raised, r.mesh, r.check);
    OptimParams untangle = params.optim;
    untangle.method = OptimParams::Method::Untangle;
    optimize(r.mesh, &r.primal, untangle, {}, seed, r.check.verdicts);
    lap("optimize");
    r.check = check_mesh(r.mesh, &r.primal, false);
    lap("star_test_after");
  }
  j.set("invalid_after", r.check.invalid_cells);
  j.set("cells_rechecked", rs.rechecked);
  j.set("seconds", sec);
  return j;
}

// Per vertex (internal numbering), its cells that `check` found invalid.
std::vector<std::uint32_t> invalid_per_vertex(const SplitState& st, const PolyMesh& mesh, const CheckResult& check) {
  std::vector<std::uint32_t> bad(st.whole.size(), 0);
  for (std::size_t c = 0; c < check.verdicts.size(); ++c)
    bad[st.internal_of_input[mesh.cell_primal[c].idx].idx] += !check.verdicts[c].valid;
  return bad;
}

// The vertices with an invalid cell (bad: per vertex, its invalid cells) not
// yet whole, now marked whole, increasing.
std::vector<VertexId> escalate_vertices(SplitState& st, const ClassifiedTetMesh& m,
                                        const std::vector<std::uint32_t>& bad) {
  std::vector<VertexId> raised;
  for (std::size_t v = 0; v < bad.size(); ++v) {
    if (!bad[v] || st.whole[v]) continue;
    st.whole[v] = 1;
    if (st.cause[v] == CutCause::None) st.cause[v] = invalid_cause(m, VertexId(v));
    raised.push_back(VertexId(v));
  }
  return raised;
}

// The whole rebuild with the union of cuts and its exact check, into r. Its
// cells' origins (split/warm_start.h) are found before the build, while no
// dual is alive: afterwards their side tables would sit on the peak.
Json whole_build(ConvertResult& r, SplitState& st, const PipelineParams& params) {
  Json sec = Json::object();
  Stopwatch w;
  st.cuts = union_of_cuts(st, r.primal);
  std::vector<CellId> origin = st.cuts.empty() ? std::vector<CellId>() : cut_cell_origins(r.primal, st.cuts);
  sec.set("cuts", w.seconds());
  w = Stopwatch();
  DualStats ds;
  r.mesh = build_dual(r.primal, params.dual, &ds, &st.cuts);
  if (!origin.empty() && origin.size() == r.mesh.num_cells()) r.mesh.cell_origin = std::move(origin);
  sec.set("dual", w.seconds());
  sec.set("dual_parts", ds.to_json());
  w = Stopwatch();
  r.check = check_mesh(r.mesh, &r.primal, false);
  sec.set("star_test", w.seconds());
  Json j = Json::object();
  j.set("local", false);
  j.set("vertices_whole", num_whole(st));
  j.set("cells", r.mesh.num_cells());
  j.set("invalid_after", r.check.invalid_cells);
  j.set("cells_rechecked", r.mesh.num_cells());
  j.set("seconds", sec);
  return j;
}

// The split's rounds without an optimiser (split/local_round.h): the current
// mesh is freed, each round rebuilds and star-tests only the cells around the
// vertices it cuts whole, and one whole build with every cut, checked
// exactly, ends them (its record is the last of `rounds`). Returns the
// number of local rounds run (at most params.split.max_rounds); none (and
// r untouched) when no vertex is to be cut.
int run_local_rounds(ConvertResult& r, SplitState& st, const PipelineParams& params, const ConvertHooks& hooks,
                     Json& rounds) {
  const Stopwatch clock;
  std::vector<std::uint32_t> bad = invalid_per_vertex(st, r.mesh, r.check);
  std::vector<VertexId> raised = escalate_vertices(st, r.primal, bad);
  if (raised.empty()) return 0;
  r.mesh = PolyMesh{};  // the final build replaces it: one whole dual alive at a time
  r.check = CheckResult{};
  const double collapse = dual_collapse_length(r.primal, params.dual);
  int k = 0;
  while (!raised.empty()) {
    throw_if_interrupted();
    // The cells of a vertex cut whole are barycentric corners, not tested by
    // the local rounds (split/local_round.h); the final whole build does.
    for (VertexId d : raised) bad[d.idx] = 0;
    const LocalRound lr = local_round(r.primal, st.free_edge, st.whole, raised, params.dual, collapse);
    for (std::size_t i = 0; i < lr.vertices.size(); ++i) bad[lr.vertices[i].idx] = lr.invalid[i];
    std::size_t invalid = 0;
    for (std::uint32_t b : bad) invalid += b;
    Json j = Json::object();
    j.set("local", true);
    j.set("vertices_whole", num_whole(st));
    j.set("on_whole_mesh", lr.on_whole_mesh);
    j.set("tets", lr.tets);
    j.set("invalid_after", invalid);
    j.set("cells_rechecked", lr.cells_tested);
    j.set("seconds", lr.seconds);
    split_progress(hooks, params, clock, k + 1, invalid, st);
    rounds.push(std::move(j));
    if (++k == params.split.max_rounds) break;
    raised = escalate_vertices(st, r.primal, bad);
  }
  rounds.push(whole_build(r, st, params));
  return k;
}

// Cells of the uncut dual that were split, by the cause of their vertex; and
// the cells still invalid.
Json split_causes(const ConvertResult& r, const SplitState& st) {
  std::size_t n[6] = {0, 0, 0, 0, 0, 0};
  std::vector<char> seen(r.mesh.cell_origin.size(), 0);
  for (std::size_t c = 0; c < r.mesh.cell_origin.size(); ++c) {
    const CellId o = r.mesh.cell_origin[c];
    const VertexId v = st.internal_of_input[r.mesh.cell_primal[c].idx];
    if (o.idx >= seen.size() || seen[o.idx] || st.cuts.of(v).empty()) continue;
    seen[o.idx] = 1;
    ++n[int(st.cause[v.idx])];
  }
  Json j = Json::object();
  for (CutCause k : {CutCause::FreeEdge, CutCause::SheetCrossing, CutCause::ConcaveEdge, CutCause::ConcaveVertex,
                     CutCause::Other})
    j.set(cut_cause_name(k), n[int(k)]);
  j.set("still_invalid", r.check.invalid_cells);
  // Of those, the cells of whole vertices: barycentric corners, convex in
  // exact arithmetic; only the rounding of their points could leave one
  // (proofs/split.md T1). Expected 0.
  std::size_t corners = 0;
  for (std::size_t c = 0; c < r.check.verdicts.size(); ++c)
    corners += !r.check.verdicts[c].valid && st.cuts.is_whole(st.internal_of_input[r.mesh.cell_primal[c].idx]);
  j.set("still_invalid_whole", corners);
  return j;
}

// The cells `check` found invalid, as (vertex, side): the primal vertex
// (internal numbering) and the cell's rank among that vertex's cells.
std::vector<BadCell> bad_cells(const SplitState& st, const PolyMesh& mesh, const CheckResult& check) {
  std::vector<BadCell> bad;
  std::uint32_t rank = 0;
  for (std::size_t c = 0; c < check.verdicts.size(); ++c) {
    rank = c > 0 && mesh.cell_primal[c] == mesh.cell_primal[c - 1] ? rank + 1 : 0;
    if (!check.verdicts[c].valid) bad.push_back({st.internal_of_input[mesh.cell_primal[c].idx], rank});
  }
  return bad;
}

// Per vertex (internal numbering) cut whole in `cuts`, the worst quality of
// its cells in `mesh` (others 0); `bad` receives, as (vertex, side), the
// valid cells of whole vertices above max(bound, worst[v]) when worst is given.
std::vector<double> whole_cell_quality(const SplitState& st, const VertexCuts& cuts, const PolyMesh& mesh,
                                       const CheckResult& check, Metric metric, const std::vector<double>* worst,
                                       double bound, std::vector<BadCell>* bad) {
  std::vector<double> q(st.whole.size(), 0.0);
  const MeshStencil s = build_stencil(mesh);
  std::uint32_t rank = 0;
  for (std::size_t c = 0; c < mesh.num_cells(); ++c) {
    rank = c > 0 && mesh.cell_primal[c] == mesh.cell_primal[c - 1] ? rank + 1 : 0;
    const VertexId v = st.internal_of_input[mesh.cell_primal[c].idx];
    if (!cuts.is_whole(v) || !check.verdicts[c].valid) continue;
    const double cq = cell_quality(s, std::uint32_t(c), metric, mesh.points);
    q[v.idx] = std::max(q[v.idx], cq);
    if (worst && bad && cq > std::max(bound, (*worst)[v.idx])) bad->push_back({v, rank});
  }
  return q;
}

// Merges the barycentric corners of the whole vertices back while every cell
// stays valid (split/coarsen.h). A trial is the dual rebuilt with the trial's
// cuts, every point at its position in the last valid mesh (the base: r's at
// first; merging keeps every point, dual/cut_topology.h kCentre), star-tested
// exactly (cells equal to one of the base keep their verdict). A merged cell
// whose quality is above both kMergeQualityBound and the worst of its
// vertex's corners counts as a failure too (floating point: it only steers
// the merging), so merging does not make a vertex's worst cell worse. A
// trial with no failure becomes the base; the last base replaces r's mesh,
// and the split's final optimisation then smooths it. (Untangling each trial
// before judging it kept 7-30 % more merges but cost up to 19 s on a
// 13k-tet TetGen mesh against 0.5 s: measured.)
Json coarsen_split(ConvertResult& r, SplitState& st, const PipelineParams& params) {
  const Stopwatch clock;
  VertexCuts base_cuts = st.cuts;
  const Metric metric = params.optim.metric;
  const std::vector<double> worst =
      whole_cell_quality(st, st.cuts, r.mesh, r.check, metric, nullptr, kMergeQualityBound, nullptr);
  auto evaluate = [&](const VertexCuts& cuts) {
    PolyMesh fresh = build_dual(r.primal, params.dual, nullptr, &cuts);
    const std::vector<PointId> from_old = warm_start_by_rank(fresh, r.mesh);
    CheckResult check = recheck_mesh(fresh, r.mesh, r.check, from_old);
    std::vector<BadCell> bad = bad_cells(st, fresh, check);
    whole_cell_quality(st, cuts, fresh, check, metric, &worst, kMergeQualityBound, &bad);
    if (bad.empty()) {
      r.mesh = std::move(fresh);
      r.check = std::move(check);
      base_cuts = cuts;
    }
    return bad;
  };
  const std::size_t cells_before = r.mesh.num_cells();
  CoarsenStats cs;
  const VertexCuts coarse = coarsen_whole_cuts(r.primal, st.free_edge, st.cuts.whole, evaluate, &cs);
  Json j = cs.to_json();
  j.set("cells_before", cells_before);
  j.set("cells_after", r.mesh.num_cells());
  // The coarsening ends on the cuts of its last valid trial (or where it began).
  if (!(coarse.tri == base_cuts.tri) || !(coarse.whole == base_cuts.whole))
    throw std::logic_error("coarsen_split: the coarsened cuts are not those of the last valid trial");
  st.cuts = std::move(base_cuts);
  j.set("seconds", clock.seconds());
  return j;
}

// The rounds of the split loop after the first optimised dual (split/split.h):
// the vertices of the cells still invalid are cut whole, the dual rebuilt and
// checked, until no cell is invalid or every invalid cell is already a
// barycentric corner (convex by construction: only rounding could leave one
// invalid) or max_rounds. The mesh with the fewest invalid cells is kept (the
// earliest among equals), so the split never makes the result worse
// (proofs/split.md, T2); if it is a split one it is optimised once more (the
// optimiser keeps every valid cell valid, exactly), near the cuts only.
// Without an optimiser the rounds are local first (run_local_rounds).
void run_split(ConvertResult& r, SplitState& st, const PipelineParams& params, const ConvertHooks& hooks) {
  run_stage(r.report, hooks, "split", [&](Json& stats) {
    const Stopwatch clock;
    Json rounds = Json::array();
    // The best mesh so far is r.mesh itself (best_is_current) or, when later
    // rounds did worse, kept apart: it is moved aside, never copied.
    PolyMesh best_mesh;
    CheckResult best_check;
    VertexCuts best_cuts;
    bool best_is_current = true;
    std::size_t best_invalid = r.check.invalid_cells;
    int best_round = 0, k0 = 0;
    if (params.optim.method == OptimParams::Method::None && best_invalid > 0 && params.split.max_rounds > 0) {
      // No optimised positions to warm-start from: local rounds (their
      // verdicts are the whole mesh's, proofs/split.md L5), then one whole
      // build, exactly checked. T2 compares it with the first dual, which
      // (unoptimised) is rebuilt when it was no worse.
      k0 = run_local_rounds(r, st, params, hooks, rounds);  // 0: nothing cut, r as it was
      if (k0 > 0 && r.check.invalid_cells < best_invalid) {
        best_invalid = r.check.invalid_cells;
        best_round = k0;
      } else if (k0 > 0) {
        best_is_current = false;
        best_cuts = st.free_edge;
        best_mesh = build_dual(r.primal, params.dual, nullptr, best_cuts.empty() ? nullptr : &best_cuts);
        best_check = check_mesh(best_mesh, &r.primal, false);
      }
    }
    // Keeps the round just run if it is the best so far, else keeps (moves
    // aside) the best one.
    auto keep_best = [&](PolyMesh&& old, CheckResult&& old_check, VertexCuts&& old_cuts, int round) {
      if (r.check.invalid_cells < best_invalid) {
        best_is_current = true;
        best_invalid = r.check.invalid_cells;
        best_round = round;
        best_mesh = PolyMesh{};
        best_check = CheckResult{};
        best_cuts = VertexCuts{};
      } else if (best_is_current) {
        best_is_current = false;
        best_mesh = std::move(old);
        best_check = std::move(old_check);
        best_cuts = std::move(old_cuts);
      }
    };
    // One round: cuts whole the vertices of the invalid cells not yet whole
    // (false when there is none, unless `rebuild`: the closure's first round,
    // after an optimiser that may have moved pinned points), rebuilds,
    // checks, re-optimises if asked.
    int k = k0, closure_rounds = 0;
    auto round = [&](bool reoptimise, bool rebuild) {
      throw_if_interrupted();
      const std::vector<VertexId> raised = escalate_vertices(st, r.primal, invalid_per_vertex(st, r.mesh, r.check));
      if (raised.empty() && !rebuild) return false;
      PolyMesh old = std::move(r.mesh);
      CheckResult old_check = std::move(r.check);
      VertexCuts old_cuts = std::move(st.cuts);
      rounds.push(split_round(r, old, old_check, st, params, raised, reoptimise));
      split_progress(hooks, params, clock, ++k, r.check.invalid_cells, st);
      keep_best(std::move(old), std::move(old_check), std::move(old_cuts), k);
      return true;
    };
    const bool optimise = params.optim.method != OptimParams::Method::None;
    const int first = k;
    while (k < params.split.max_rounds && r.check.invalid_cells > 0 && round(optimise, false)) {
    }
    // The closure (proofs/split.md, T1): rounds without re-optimisation, not
    // bounded by max_rounds, every pinned point at its barycentre, until
    // every invalid cell is a cell of a whole vertex. The whole set grows in
    // every round after the first, so at most |V| + 1 rounds; at worst every
    // vertex is whole and the dual is the barycentric subdivision, whose cells
    // are all convex (proofs/dual_cuts.md C5). Its first round rebuilds even
    // when no vertex is newly cut if the rounds before re-optimised (pinned
    // points may have moved).
    if (params.split.max_rounds > 0) {
      bool rebuild = optimise && k > first;
      while (r.check.invalid_cells > 0 && round(false, rebuild)) {
        rebuild = false;
        ++closure_rounds;
      }
    }
    if (!best_is_current) {
      r.mesh = std::move(best_mesh);
      r.check = std::move(best_check);
      st.cuts = std::move(best_cuts);
    }
    stats = Json::object();
    if (params.split.coarsen && r.check.invalid_cells == 0 && st.cuts.any_whole())
      stats.set("coarsen", coarsen_split(r, st, params));
    if (best_round > 0 && params.optim.method != OptimParams::Method::None) {
      const std::vector<char> seed = split_region(r.primal, st.cuts, r.mesh);
      const bool local = params.optim.method != OptimParams::Method::Global;
      stats.set("optimize", optimize(r.mesh, &r.primal, params.optim, hooks.progress,
                                     local ? std::span<const char>(seed) : std::span<const char>(),
                                     r.check.verdicts)
                                .to_json());
      r.check = check_mesh(r.mesh, &r.primal, false);
    }
    // The final whole build of the local rounds has them already.
    if (!st.cuts.empty() && r.mesh.cell_origin.empty())
      r.mesh.cell_origin = cut_cell_origins(r.primal, st.cuts, r.mesh);
    stats.set("rounds", rounds);
    stats.set("kept_round", best_round);
    stats.set("closure_rounds", closure_rounds);
    stats.set("free_edge_vertices", st.free_edge.num_vertices_cut());
    stats.set("vertices_cut", st.cuts.num_vertices_cut());
    stats.set("cells_split", split_causes(r, st));
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
    const ModelRef cls = in.idx < internal.size() && internal[in.idx].valid() ? r.primal.vertex_class(internal[in.idx])
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
  std::string what;
  if (!defects.empty()) what = "the dual is not sound: " + defects_sentence(defects) + (r.check.invalid_cells ? "; " : "");
  if (r.check.invalid_cells == 0) throw InputError(r.primal.source(), "", what);
  what += std::to_string(r.check.invalid_cells) + " cells remain invalid after the split:";
  for (const std::string& item : invalid_cell_items(r, r.check.invalid_cells)) what += " " + item + ";";
  throw InputError(r.primal.source(), "", what);
}

// The stages from classify to the final check, appended to r.report. A soup
// the caller owns (`release`, may be null) is freed once classified: it is
// not needed after, and the split rounds are the memory peak.
void run_pipeline(ConvertResult& r, const TetSoup& soup, const PipelineParams& params, const ConvertHooks& hooks,
                  TetSoup* release = nullptr) {
  ConvertReport& rep = r.report;
  r.ignored = soup.ignored;
  r.warnings = soup.warnings;
  r.primal = run_stage(rep, hooks, "classify", [&](Json& stats) {
    ClassifyStats st;
    ClassifiedTetMesh m = classify(soup, params.classify, &st);
    stats = st.to_json();
    return m;
  });
  if (release) *release = TetSoup{};
  if (params.tetopt.enabled)
    run_stage(rep, hooks, "optimize_tets", [&](Json& stats) { stats = optimize_tets(r.primal, params.tetopt).to_json(); return 0; });
  // What the classification completed (an incomplete given classification).
  for (const std::string& w : r.primal.classification_warnings()) r.warnings.push_back(w);
  SplitState st;
  if (params.split.enabled) {
    st.free_edge = run_stage(rep, hooks, "cuts", [&](Json& stats) {
      VertexCuts c = free_edge_cuts(r.primal);
      stats = Json::object();
      stats.set("free_edge_vertices", c.num_vertices_cut());
      return c;
    });
    st.cuts = st.free_edge;
    st.whole.assign(r.primal.num_vertices(), 0);
    st.cause.assign(r.primal.num_vertices(), CutCause::None);
    for (std::size_t v = 0; v < st.whole.size(); ++v)
      if (!st.free_edge.of(VertexId(v)).empty()) st.cause[v] = CutCause::FreeEdge;
    st.internal_of_input = internal_of_input(r.primal);
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
  if (optimise) {
    run_stage(rep, hooks, "optimize", [&](Json& stats) {
      stats = optimize(r.mesh, &r.primal, params.optim, hooks.progress, {}, r.check.verdicts).to_json();
      return 0;
    });
    // With the split, check_split validates the mesh that is returned.
    r.check = run_stage(rep, hooks, "check_after", [&](Json& stats) {
      CheckResult c = check_mesh(r.mesh, &r.primal, !params.split.enabled);
      stats = c.to_json();
      return c;
    });
  }
  if (params.split.enabled) run_split(r, st, params, hooks);
  if (params.dual.boundary == BoundaryMode::Caps) warn_lost_volume(r);
  rep.invalid_after = r.check.invalid_cells;
  if (params.split.require_valid) require_valid(r);
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
  return write_poly_mesh(r.mesh, path, format, WriteContext{options, std::move(fields), model_names(r.primal.model())});
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
  r.optim = optimize(mesh, primal, params, progress);
  r.check = check_mesh(mesh, primal);
  return r;
}

}  // namespace polydual
