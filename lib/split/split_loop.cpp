// The split loop (split/split.h): rounds, escalation, warm start, closure and
// the re-optimisation of the mesh kept. Proofs and guarantees:
// proofs/split.md (T1 the closure ends with every cell valid, T2 the result
// is never worse than the first dual, L4 reused verdicts, L5 local rounds).
#include <algorithm>
#include <cstdio>
#include <optional>

#include "core/interrupt.h"
#include "core/stopwatch.h"
#include "dual/cut_topology.h"
#include "split/coarsen.h"
#include "split/local_round.h"
#include "split/recheck.h"
#include "split/split.h"
#include "split/warm_start.h"

namespace polydual {

namespace {

std::size_t num_whole(const SplitState& st) { return std::size_t(std::count(st.whole.begin(), st.whole.end(), char(1))); }

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

// Cells of the uncut dual that were split, by the cause of their vertex; and
// the cells still invalid.
Json split_causes(const PolyMesh& mesh, const CheckResult& check, const SplitState& st) {
  std::size_t n[6] = {0, 0, 0, 0, 0, 0};
  std::vector<char> seen(mesh.cell_origin.size(), 0);
  for (std::size_t c = 0; c < mesh.cell_origin.size(); ++c) {
    const CellId o = mesh.cell_origin[c];
    const VertexId v = st.internal_of_input[mesh.cell_primal[c].idx];
    if (o.idx >= seen.size() || seen[o.idx] || st.cuts.of(v).empty()) continue;
    seen[o.idx] = 1;
    ++n[int(st.cause[v.idx])];
  }
  Json j = Json::object();
  for (CutCause k : {CutCause::FreeEdge, CutCause::SheetCrossing, CutCause::ConcaveEdge, CutCause::ConcaveVertex,
                     CutCause::Other})
    j.set(cut_cause_name(k), n[int(k)]);
  j.set("still_invalid", check.invalid_cells);
  // Of those, the cells of whole vertices: barycentric corners, convex in
  // exact arithmetic; only the rounding of their points could leave one
  // (proofs/split.md T1). Expected 0.
  std::size_t corners = 0;
  for (std::size_t c = 0; c < check.verdicts.size(); ++c)
    corners += !check.verdicts[c].valid && st.cuts.is_whole(st.internal_of_input[mesh.cell_primal[c].idx]);
  j.set("still_invalid_whole", corners);
  return j;
}

// The cells of mesh_ that OpenFOAM's checks fail, and their vertices
// (internal numbering).
struct FoamFailures {
  std::vector<std::uint32_t> cells;
  std::vector<VertexId> vertices;
};
// A cut step of the OpenFOAM rounds: its record, and whether it was undone.
struct FoamCut {
  Json record;
  bool undone = false;
  FoamFailures after;  // the cells failing after a cut kept
};

// One run of the loop: its inputs, the current mesh and check (the caller's,
// updated in place), the best mesh so far and the rounds' records.
class SplitLoop {
 public:
  SplitLoop(const ClassifiedTetMesh& m, const DualParams& dual, const SplitParams& params, SplitState& st,
            PolyMesh& mesh, CheckResult& check, const SplitHooks& hooks)
      : m_(m), dual_(dual), params_(params), st_(st), mesh_(mesh), check_(check), hooks_(hooks),
        best_invalid_(check.invalid_cells) {}
  Json run();

 private:
  void progress(const Stopwatch& clock, int round, std::size_t invalid) const;
  Json split_round(const PolyMesh& old, const CheckResult& old_check, std::span<const VertexId> raised,
                   bool reoptimise, const VertexCuts* cuts = nullptr);
  Json whole_build();
  Json local_round_record(const LocalRound& lr, std::size_t invalid) const;
  int run_local_rounds();
  void start_local();
  void keep_best(PolyMesh&& old, CheckResult&& old_check, VertexCuts&& old_cuts);
  bool round(bool reoptimise, bool rebuild);
  void closure(int first);
  Json foam_rounds();
  FoamFailures foam_failures() const { return failures_of(hooks_.foam_failing(mesh_)); }
  FoamFailures failures_of(std::vector<std::uint32_t> cells) const;
  std::optional<FoamCut> foam_cut(const FoamFailures& f);
  std::size_t foam_repin(const FoamFailures& f);
  Json finish();

  const ClassifiedTetMesh& m_;
  const DualParams& dual_;
  const SplitParams& params_;
  SplitState& st_;
  PolyMesh& mesh_;
  CheckResult& check_;
  const SplitHooks& hooks_;
  const Stopwatch clock_;
  Json rounds_ = Json::array();
  // The best mesh so far is mesh_ itself (best_is_current_) or, when later
  // rounds did worse, kept apart: it is moved aside, never copied.
  PolyMesh best_mesh_;
  CheckResult best_check_;
  VertexCuts best_cuts_;
  bool best_is_current_ = true;
  std::size_t best_invalid_;
  int best_round_ = 0, k_ = 0, closure_rounds_ = 0;
};

// A split round's progress (the command shows it when the stage runs long).
void SplitLoop::progress(const Stopwatch& clock, int round, std::size_t invalid) const {
  if (!hooks_.progress) return;
  char detail[128];
  std::snprintf(detail, sizeof detail, "invalid cells %zu, vertices cut whole %zu", invalid, num_whole(st_));
  hooks_.progress(ProgressEvent{"split", round, params_.max_rounds, clock.seconds(), detail});
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
// mesh_ and check_; returns the round's record.
Json SplitLoop::split_round(const PolyMesh& old, const CheckResult& old_check, std::span<const VertexId> raised,
                            bool reoptimise, const VertexCuts* cuts) {
  Json sec = Json::object();  // the round's parts, wall seconds
  Stopwatch w;
  auto lap = [&](const char* part) {
    sec.set(part, w.seconds());
    w = Stopwatch();
  };
  st_.cuts = cuts ? *cuts : with_whole_cuts(m_, st_.free_edge, st_.whole);
  lap("cuts");
  DualStats ds;
  PolyMesh fresh = build_dual(m_, dual_, &ds, &st_.cuts);
  lap("dual");
  sec.set("dual_parts", ds.to_json());
  Json j = Json::object();
  j.set("local", false);
  j.set("closure", !reoptimise);
  j.set("vertices_whole", num_whole(st_));
  j.set("cells", fresh.num_cells());
  std::vector<PointId> from_old;
  j.set("points_warm_started", warm_start(fresh, old, m_, st_.cuts, &from_old));
  lap("warm_start");
  RecheckStats rs;
  check_ = recheck_mesh(fresh, old, old_check, from_old, &rs);
  lap("star_test");
  mesh_ = std::move(fresh);
  j.set("invalid_built", check_.invalid_cells);
  if (reoptimise && check_.invalid_cells > 0) {
    // Untangling only: validity is what decides the next round's cuts; the
    // kept mesh is smoothed once at the end (finish).
    const std::vector<char> seed = round_seed(m_, raised, mesh_, check_);
    hooks_.optimise(mesh_, seed, check_.verdicts, true);
    lap("optimize");
    check_ = check_mesh(mesh_, &m_, false);
    lap("star_test_after");
  }
  j.set("invalid_after", check_.invalid_cells);
  j.set("cells_rechecked", rs.rechecked);
  j.set("seconds", sec);
  return j;
}

// The whole rebuild with the union of cuts and its exact check. Its cells'
// origins (split/warm_start.h) are found before the build, while no dual is
// alive: afterwards their side tables would sit on the peak.
Json SplitLoop::whole_build() {
  Json sec = Json::object();
  Stopwatch w;
  st_.cuts = with_whole_cuts(m_, st_.free_edge, st_.whole);
  std::vector<CellId> origin = st_.cuts.empty() ? std::vector<CellId>() : cut_cell_origins(m_, st_.cuts);
  sec.set("cuts", w.seconds());
  w = Stopwatch();
  DualStats ds;
  mesh_ = build_dual(m_, dual_, &ds, &st_.cuts);
  if (!origin.empty() && origin.size() == mesh_.num_cells()) mesh_.cell_origin = std::move(origin);
  sec.set("dual", w.seconds());
  sec.set("dual_parts", ds.to_json());
  w = Stopwatch();
  check_ = check_mesh(mesh_, &m_, false);
  sec.set("star_test", w.seconds());
  Json j = Json::object();
  j.set("local", false);
  j.set("vertices_whole", num_whole(st_));
  j.set("cells", mesh_.num_cells());
  j.set("invalid_after", check_.invalid_cells);
  j.set("cells_rechecked", mesh_.num_cells());
  j.set("seconds", sec);
  return j;
}

// A local round's record; invalid: the invalid cells of every vertex after it.
Json SplitLoop::local_round_record(const LocalRound& lr, std::size_t invalid) const {
  Json j = Json::object();
  j.set("local", true);
  j.set("vertices_whole", num_whole(st_));
  j.set("on_whole_mesh", lr.on_whole_mesh);
  j.set("tets", lr.tets);
  j.set("invalid_after", invalid);
  j.set("cells_rechecked", lr.cells_tested);
  j.set("seconds", lr.seconds);
  return j;
}

// The split's rounds without an optimiser (split/local_round.h): the current
// mesh is freed, each round rebuilds and star-tests only the cells around the
// vertices it cuts whole, and one whole build with every cut, checked
// exactly, ends them (its record is the last of rounds_). Returns the number
// of local rounds run (at most max_rounds); none (and the mesh untouched)
// when no vertex is to be cut.
int SplitLoop::run_local_rounds() {
  const Stopwatch clock;
  std::vector<std::uint32_t> bad = invalid_per_vertex(st_, mesh_, check_);
  std::vector<VertexId> raised = escalate_vertices(st_, m_, bad);
  if (raised.empty()) return 0;
  mesh_ = PolyMesh{};  // the final build replaces it: one whole dual alive at a time
  check_ = CheckResult{};
  const double collapse = dual_collapse_length(m_, dual_);
  int k = 0;
  while (!raised.empty()) {
    throw_if_interrupted();
    // The cells of a vertex cut whole are barycentric corners, not tested by
    // the local rounds (split/local_round.h); the final whole build does.
    for (VertexId d : raised) bad[d.idx] = 0;
    const LocalRound lr = local_round(m_, st_.free_edge, st_.whole, raised, dual_, collapse);
    for (std::size_t i = 0; i < lr.vertices.size(); ++i) bad[lr.vertices[i].idx] = lr.invalid[i];
    std::size_t invalid = 0;
    for (std::uint32_t b : bad) invalid += b;
    progress(clock, k + 1, invalid);
    rounds_.push(local_round_record(lr, invalid));
    if (++k == params_.max_rounds) break;
    raised = escalate_vertices(st_, m_, bad);
  }
  rounds_.push(whole_build());
  return k;
}

// No optimised positions to warm-start from: local rounds (their verdicts
// are the whole mesh's, proofs/split.md L5), then one whole build, exactly
// checked. T2 compares it with the first dual, which (unoptimised) is
// rebuilt when it was no worse.
void SplitLoop::start_local() {
  k_ = run_local_rounds();  // 0: nothing cut, the mesh as it was
  if (k_ > 0 && check_.invalid_cells < best_invalid_) {
    best_invalid_ = check_.invalid_cells;
    best_round_ = k_;
  } else if (k_ > 0) {
    best_is_current_ = false;
    best_cuts_ = st_.free_edge;
    best_mesh_ = build_dual(m_, dual_, nullptr, best_cuts_.empty() ? nullptr : &best_cuts_);
    best_check_ = check_mesh(best_mesh_, &m_, false);
  }
}

// Keeps the round just run if it is the best so far, else keeps (moves
// aside) the best one.
void SplitLoop::keep_best(PolyMesh&& old, CheckResult&& old_check, VertexCuts&& old_cuts) {
  if (check_.invalid_cells < best_invalid_) {
    best_is_current_ = true;
    best_invalid_ = check_.invalid_cells;
    best_round_ = k_;
    best_mesh_ = PolyMesh{};
    best_check_ = CheckResult{};
    best_cuts_ = VertexCuts{};
  } else if (best_is_current_) {
    best_is_current_ = false;
    best_mesh_ = std::move(old);
    best_check_ = std::move(old_check);
    best_cuts_ = std::move(old_cuts);
  }
}

// One round: cuts whole the vertices of the invalid cells not yet whole
// (false when there is none, unless `rebuild`: the closure's first round,
// after an optimiser that may have moved pinned points), rebuilds, checks,
// re-optimises if asked.
bool SplitLoop::round(bool reoptimise, bool rebuild) {
  throw_if_interrupted();
  const std::vector<VertexId> raised = escalate_vertices(st_, m_, invalid_per_vertex(st_, mesh_, check_));
  if (raised.empty() && !rebuild) return false;
  PolyMesh old = std::move(mesh_);
  CheckResult old_check = std::move(check_);
  VertexCuts old_cuts = std::move(st_.cuts);
  rounds_.push(split_round(old, old_check, raised, reoptimise));
  progress(clock_, ++k_, check_.invalid_cells);
  keep_best(std::move(old), std::move(old_check), std::move(old_cuts));
  return true;
}

// The closure (proofs/split.md, T1): rounds without re-optimisation, not
// bounded by max_rounds, every pinned point at its barycentre, until every
// invalid cell is a cell of a whole vertex. The whole set grows in every
// round after the first, so at most |V| + 1 rounds; at worst every vertex is
// whole and the dual is the barycentric subdivision, whose cells are all
// convex (proofs/dual_cuts.md C5). Its first round rebuilds even when no
// vertex is newly cut if the rounds before re-optimised (pinned points may
// have moved); first: the round count before them.
void SplitLoop::closure(int first) {
  bool rebuild = bool(hooks_.optimise) && k_ > first;
  while (check_.invalid_cells > 0 && round(false, rebuild)) {
    rebuild = false;
    ++closure_rounds_;
  }
}

// Cells that OpenFOAM's checks still fail once the kept mesh is optimised
// (the optimiser's repair could not move them) are made barycentric corners
// (proofs/dual_cuts.md C5: convex with planar faces, which OpenFOAM's
// decomposition passes up to rounding): in each of at most kFoamRounds
// rounds,
//  - cut: a failing cell's vertex not yet whole is cut whole, as for an
//    invalid cell, and a failing union of corners that the coarsening made
//    is split back (split_back); the dual is rebuilt with warm-started
//    points, re-optimised near the cuts and checked exactly;
//  - re-pin: the points of a failing corner that the optimiser moved off
//    their barycentres (a model-face point sliding onto the next facet
//    of a curved face leaves the corner's faces warped) are put back, in
//    place, and the mesh checked exactly.
// A step that leaves a cell invalid by the exact test is undone (validity
// first), and so is a cut after which as many cells fail OpenFOAM's checks;
// the rounds stop at the first that changes nothing, and a cut undone is
// not tried again (proofs/split.md L7). The rounds' records.
Json SplitLoop::foam_rounds() {
  constexpr int kFoamRounds = 3;
  Json records = Json::array();
  bool cut_undone = false;  // the same cut would be undone again: not retried
  for (int i = 0; i < kFoamRounds; ++i) {
    FoamFailures f = foam_failures();
    if (f.cells.empty()) break;
    Json r = Json::object();
    r.set("failing_cells", f.cells.size());
    bool changed = false;
    if (std::optional<FoamCut> cut = cut_undone ? std::nullopt : foam_cut(f)) {
      cut_undone = cut->undone;
      changed = !cut->undone;
      r.set("cut", std::move(cut->record));
      if (changed) f = std::move(cut->after);
    }
    const std::size_t repinned = foam_repin(f);
    r.set("repinned_points", repinned);
    records.push(std::move(r));
    if (!changed && repinned == 0) break;  // nothing moved: the next round would do the same
  }
  return records;
}

FoamFailures SplitLoop::failures_of(std::vector<std::uint32_t> cells) const {
  FoamFailures f;
  f.cells = std::move(cells);
  for (std::uint32_t c : f.cells) f.vertices.push_back(st_.internal_of_input[mesh_.cell_primal[c].idx]);
  return f;
}

// The cut step of foam_rounds; none when it changes no cut.
std::optional<FoamCut> SplitLoop::foam_cut(const FoamFailures& f) {
  std::vector<std::uint32_t> bad(st_.whole.size(), 0);
  std::vector<BadCell> merged;
  for (std::size_t k = 0; k < f.cells.size(); ++k) {
    if (st_.whole[f.vertices[k].idx]) merged.push_back({f.vertices[k], cell_side(mesh_, f.cells[k])});
    else ++bad[f.vertices[k].idx];
  }
  const std::vector<char> whole_before = st_.whole;
  const std::vector<CutCause> cause_before = st_.cause;
  VertexCuts cuts = split_back(m_, st_.cuts, merged);
  std::vector<char> raised(st_.whole.size(), 0);
  for (VertexId v : escalate_vertices(st_, m_, bad)) raised[v.idx] = 1;
  cuts = VertexCuts::merged(m_.num_vertices(), cuts, with_whole_cuts(m_, VertexCuts{}, raised));
  if (cuts.tri == st_.cuts.tri && cuts.whole == st_.cuts.whole) return std::nullopt;  // corners already
  std::vector<VertexId> changed = f.vertices;
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  PolyMesh old = std::move(mesh_);
  CheckResult old_check = std::move(check_);
  VertexCuts old_cuts = std::move(st_.cuts);
  Json r = split_round(old, old_check, changed, true, &cuts);
  if (check_.invalid_cells == 0) {
    r.set("optimize", hooks_.optimise(mesh_, split_region(m_, st_.cuts, mesh_), check_.verdicts, false));
    check_ = check_mesh(mesh_, &m_, false);
  }
  // Validity first; and a cut must lower the count of failing cells (the
  // corners of a cut vertex can fail in turn where no optimiser smooths).
  FoamFailures after = check_.invalid_cells > 0 ? FoamFailures{} : foam_failures();
  const bool undone = check_.invalid_cells > 0 || after.cells.size() >= f.cells.size();
  r.set("vertices", changed.size());
  r.set("undone", undone);
  if (undone) {
    mesh_ = std::move(old);
    check_ = std::move(old_check);
    st_.cuts = std::move(old_cuts);
    st_.whole = whole_before;
    st_.cause = cause_before;
  }
  return FoamCut{std::move(r), undone, std::move(after)};
}

// The re-pin step of foam_rounds: the points of failing cells of whole
// vertices that are pinned (dual/cut_topology.h) put back at their
// barycentres; the cells that turns invalid (neighbours whose other points
// the optimiser fitted to the moved ones) untangled (the optimiser's exact
// gate keeps every valid cell valid); all undone if a cell stays invalid.
// Returns the points re-pinned (0 if undone).
std::size_t SplitLoop::foam_repin(const FoamFailures& f) {
  const std::vector<Point3> before = mesh_.points;
  std::size_t moved = 0;
  CellPointScan scan(mesh_);
  for (std::size_t k = 0; k < f.cells.size(); ++k) {
    if (!st_.cuts.is_whole(f.vertices[k])) continue;
    for (PointId p : scan(CellId(f.cells[k]))) {
      const PointOrigin o = mesh_.point_origin[p.idx];
      if (!pinned(m_, &st_.cuts, o) || barycentre(m_, o) == mesh_.points[p.idx]) continue;
      mesh_.points[p.idx] = barycentre(m_, o);
      ++moved;
    }
  }
  if (moved == 0) return 0;
  // Seeds: the failing cells (the split region instead smoothed worse: 16.0
  // against 15.7 on one mesh), and while untangling the invalid ones.
  std::vector<char> seed(mesh_.num_cells(), 0);
  for (std::uint32_t k : f.cells) seed[k] = 1;
  CheckResult c = check_mesh(mesh_, &m_, false);
  if (c.invalid_cells > 0) {
    std::vector<char> untangle = seed;
    for (std::size_t k = 0; k < untangle.size(); ++k) untangle[k] |= char(!c.verdicts[k].valid);
    hooks_.optimise(mesh_, untangle, c.verdicts, true);
    c = check_mesh(mesh_, &m_, false);
  }
  if (c.invalid_cells > 0) {
    mesh_.points = before;
    return 0;
  }
  if (hooks_.optimise_foam_gated) {
    hooks_.optimise_foam_gated(mesh_, seed, c.verdicts, false);
    c = check_mesh(mesh_, &m_, false);
  }
  check_ = std::move(c);
  return moved;
}

// The best mesh back in place, its whole vertices' corners merged back
// where the exact test allows (split/coarsen.h), re-optimised near its cuts
// when it is a split one (the optimiser keeps every valid cell valid, exactly), its cells'
// origins; the stage's record.
Json SplitLoop::finish() {
  if (!best_is_current_) {
    mesh_ = std::move(best_mesh_);
    check_ = std::move(best_check_);
    st_.cuts = std::move(best_cuts_);
  }
  Json stats = Json::object();
  if (params_.coarsen && check_.invalid_cells == 0 && st_.cuts.any_whole())
    stats.set("coarsen", coarsen_split(m_, dual_, hooks_.metric, st_, mesh_, check_,
                                            hooks_.optimise ? CoarsenStart::Corners : CoarsenStart::TopDown));
  if (best_round_ > 0 && hooks_.optimise) {
    const std::vector<char> seed = split_region(m_, st_.cuts, mesh_);
    stats.set("optimize", hooks_.optimise(mesh_, seed, check_.verdicts, false));
    check_ = check_mesh(mesh_, &m_, false);
  }
  if (hooks_.foam_failing && hooks_.optimise && check_.invalid_cells == 0) stats.set("foam_rounds", foam_rounds());
  // The final whole build of the local rounds has them already.
  if (!st_.cuts.empty() && mesh_.cell_origin.empty()) mesh_.cell_origin = cut_cell_origins(m_, st_.cuts, mesh_);
  stats.set("rounds", rounds_);
  stats.set("kept_round", best_round_);
  stats.set("closure_rounds", closure_rounds_);
  stats.set("free_edge_vertices", st_.free_edge.num_vertices_cut());
  stats.set("vertices_cut", st_.cuts.num_vertices_cut());
  // Vertices whose points sit at the barycentres of their entities (cut
  // whole, possibly merged back into one cell per side by the coarsening).
  stats.set("vertices_whole", std::size_t(std::count(st_.cuts.whole.begin(), st_.cuts.whole.end(), char(1))));
  stats.set("cells_split", split_causes(mesh_, check_, st_));
  return stats;
}

// The rounds after the first dual (split/split.h): the vertices of the cells
// still invalid are cut whole, the dual rebuilt and checked, until no cell is
// invalid or max_rounds; then the closure. The mesh with the fewest invalid
// cells is kept (the earliest among equals), so the split never makes the
// result worse (proofs/split.md, T2). Without an optimiser the rounds are
// local first (run_local_rounds).
Json SplitLoop::run() {
  if (!hooks_.optimise && best_invalid_ > 0 && params_.max_rounds > 0) start_local();
  const bool optimise = bool(hooks_.optimise);
  const int first = k_;
  while (k_ < params_.max_rounds && check_.invalid_cells > 0 && round(optimise, false)) {
  }
  if (params_.max_rounds > 0) closure(first);
  return finish();
}

}  // namespace

SplitState begin_split(const ClassifiedTetMesh& m) {
  SplitState st;
  st.free_edge = free_edge_cuts(m);
  st.cuts = st.free_edge;
  st.whole.assign(m.num_vertices(), 0);
  st.cause.assign(m.num_vertices(), CutCause::None);
  for (std::size_t v = 0; v < st.whole.size(); ++v)
    if (!st.free_edge.of(VertexId(v)).empty()) st.cause[v] = CutCause::FreeEdge;
  st.internal_of_input = internal_of_input(m);
  return st;
}

Json run_split(const ClassifiedTetMesh& m, const DualParams& dual, const SplitParams& params, SplitState& st,
               PolyMesh& mesh, CheckResult& check, const SplitHooks& hooks) {
  return SplitLoop(m, dual, params, st, mesh, check, hooks).run();
}

}  // namespace polydual
