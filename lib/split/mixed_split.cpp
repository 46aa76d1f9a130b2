#include "split/mixed_split.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <span>

#include "core/interrupt.h"
#include "core/stopwatch.h"
#include "dual/cleanup.h"
#include "dual/primal_dual.h"

namespace polydual {

namespace {

// Whether the dual point of origin o is made from an entity through a
// vertex cut whole (its position is then the builder's, not a warm start).
bool touches(const PrimalMesh& m, const std::vector<char>& whole, PointOrigin o) {
  switch (o.dim) {
    case 3: return any_marked(m.cell_vertices(PrimalCellId(o.id)), whole);
    case 2: return any_marked(m.face_vertices(PrimalFaceId(o.id)), whole);
    case 1: return any_marked(m.edge(EdgeId(o.id)), whole);
    default: return whole[o.id] != 0;
  }
}

// The rounds' state: the vertices cut whole (internal numbering) and the
// internal vertex of each input number (PolyMesh::cell_primal).
struct MixedSplit {
  const PrimalMesh& m;
  const DualParams& dual;
  const SplitHooks& hooks;
  std::vector<char> whole;
  std::vector<VertexId> vertex_of_input;

  MixedSplit(const PrimalMesh& mesh, const DualParams& d, const SplitHooks& h)
      : m(mesh), dual(d), hooks(h), whole(mesh.num_vertices(), 0), vertex_of_input(internal_of_input(mesh)) {}
  bool cut_whole(const PolyMesh& mesh, std::size_t c) const {
    return whole[vertex_of_input[mesh.cell_primal[c].idx].idx] != 0;
  }

  // One round: the primal vertices of the cells `bad` are cut whole, the
  // dual rebuilt and warm-started, the corners and their neighbours
  // re-optimised, the result checked. Returns the vertices newly cut (0: no
  // progress, mesh and check unchanged).
  std::size_t round(PolyMesh& mesh, CheckResult& check, std::span<const std::uint32_t> bad) {
    std::size_t added = 0;
    for (std::uint32_t c : bad)
      if (!cut_whole(mesh, c)) whole[vertex_of_input[mesh.cell_primal[c].idx].idx] = 1, ++added;
    if (added == 0) return 0;
    DualDraft draft = build_primal_dual_draft(m, dual, nullptr, &whole);
    cleanup_dual(draft);
    PolyMesh pm = assemble_cells(std::move(draft));
    warm_start_whole(m, whole, mesh, pm);
    std::vector<char> seeds(pm.num_cells(), 0);
    for (std::size_t c = 0; c < pm.num_cells(); ++c) seeds[c] = char(cut_whole(pm, c));
    hooks.optimise(pm, seeds, {}, false);
    mesh = std::move(pm);
    check = check_mesh(mesh, nullptr, false);
    return added;
  }
};

std::vector<std::uint32_t> invalid_cells(const CheckResult& check) {
  std::vector<std::uint32_t> out;
  for (std::size_t c = 0; c < check.verdicts.size(); ++c)
    if (!check.verdicts[c].valid) out.push_back(std::uint32_t(c));
  return out;
}

// Cells that OpenFOAM's checks fail (hooks.foam_failing) once no cell is
// invalid get their vertices cut whole too, as the tet split does
// (split_loop.cpp's foam rounds): a round that leaves a cell invalid by the
// exact test is undone. At most kFoamRounds; returns the vertices cut.
std::size_t foam_rounds(MixedSplit& split, PolyMesh& mesh, CheckResult& check) {
  constexpr int kFoamRounds = 3;
  std::size_t cut = 0;
  for (int i = 0; i < kFoamRounds && check.invalid_cells == 0; ++i) {
    const std::vector<std::uint32_t> failing = split.hooks.foam_failing(mesh);
    // Nothing to cut (every failing cell a corner already): no copy to undo.
    if (std::all_of(failing.begin(), failing.end(), [&](std::uint32_t c) { return split.cut_whole(mesh, c); })) break;
    const std::vector<char> whole_before = split.whole;
    PolyMesh old = mesh;
    CheckResult old_check = check;
    const std::size_t added = split.round(mesh, check, failing);
    if (added == 0) break;
    if (check.invalid_cells > 0) {
      split.whole = whole_before;
      mesh = std::move(old);
      check = std::move(old_check);
      break;
    }
    cut += added;
  }
  return cut;
}

}  // namespace

std::size_t warm_start_whole(const PrimalMesh& m, const std::vector<char>& whole, const PolyMesh& before,
                             PolyMesh& after) {
  std::map<std::pair<int, std::uint32_t>, Point3> at;
  for (std::size_t p = 0; p < before.num_points(); ++p)
    at.emplace(std::pair<int, std::uint32_t>{before.point_origin[p].dim, before.point_origin[p].id}, before.points[p]);
  std::size_t moved = 0;
  for (std::size_t p = 0; p < after.num_points(); ++p) {
    const PointOrigin o = after.point_origin[p];
    if (touches(m, whole, o)) continue;
    if (const auto it = at.find({o.dim, o.id}); it != at.end()) after.points[p] = it->second, ++moved;
  }
  return moved;
}

MixedSplitRun run_mixed_split(const PrimalMesh& m, const DualParams& dual, const SplitParams& params,
                              PolyMesh& mesh, CheckResult& check, const SplitHooks& hooks) {
  MixedSplit split(m, dual, hooks);
  const Stopwatch clock;
  const std::size_t invalid_before = check.invalid_cells, cells_before = mesh.num_cells();
  int rounds = 0;
  std::size_t cut = 0;
  while (check.invalid_cells > 0 && rounds < params.max_rounds) {
    throw_if_interrupted();
    const std::size_t added = split.round(mesh, check, invalid_cells(check));
    if (added == 0) break;
    cut += added;
    ++rounds;
    if (hooks.progress) {
      char detail[128];
      std::snprintf(detail, sizeof detail, "invalid cells %zu, vertices cut whole %zu", check.invalid_cells, cut);
      hooks.progress(ProgressEvent{"split", rounds, params.max_rounds, clock.seconds(), detail});
    }
  }
  const std::size_t foam_cut = hooks.foam_failing ? foam_rounds(split, mesh, check) : 0;
  if (foam_cut > 0) ++rounds;
  Json stats = Json::object();
  stats.set("rounds", rounds);
  stats.set("foam_whole_vertices", foam_cut);
  stats.set("whole_vertices", cut);
  stats.set("invalid_before", invalid_before);
  stats.set("invalid_after", check.invalid_cells);
  stats.set("cells_before", cells_before);
  stats.set("cells_after", mesh.num_cells());
  return {rounds, std::move(stats)};
}

}  // namespace polydual
