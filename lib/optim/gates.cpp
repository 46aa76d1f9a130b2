// The local schemes' acceptance gates beside the exact star test (context.h).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "optim/context.h"
#include "optim/foam_gate.h"
#include "quality/metrics.h"
#include "quality/star_verdict.h"

namespace polydual::optim_detail {

void Context::init_gates() {
  if (!setup.params.foam_gate) return;
  face_base.clear();
  choose_foam_bases(mesh, setup.stencil, mesh.points, face_base);
  foam_ok.assign(setup.stencil.num_cells(), 0);
  std::vector<std::uint32_t> all(setup.stencil.num_cells());
  for (std::uint32_t c = 0; c < all.size(); ++c) all[c] = c;
  refresh_foam(all);
  lap("foam_gate");
  // Without foam_gate_sweeps the sweeps, the polish and the min-max descent
  // move freely (on sliver meshes the gate in every sweep held the worst cell
  // at 4x and the mean at 1.8x); the repair then applies it (repair_foam).
  foam_active = setup.params.foam_gate_sweeps;
}

bool Context::gates_accept(std::span<const std::uint32_t> cells, std::vector<double>& q) const {
  q.clear();
  for (std::uint32_t c : cells) {
    // Floating point, a measure (the star test decided validity already).
    q.push_back(polydual::cell_quality(setup.stencil, c, setup.params.metric, mesh.points));
    if (cell_valid[c] && !(q.back() <= std::max(cell_quality[c], quality_cap))) return false;
  }
  if (!setup.params.foam_gate || !foam_active) return true;
  for (std::uint32_t c : cells)
    if (foam_ok[c] && !foam_cell_ok(setup.stencil, c, mesh.points, face_base, setup.loop_face)) return false;
  return true;
}

void Context::gates_commit(std::span<const std::uint32_t> cells, std::span<const double> q) {
  for (std::size_t i = 0; i < cells.size(); ++i) cell_quality[cells[i]] = q[i];
  if (!setup.params.foam_gate || !foam_active) return;
  for (std::uint32_t c : cells)
    if (!foam_ok[c]) foam_ok[c] = foam_cell_ok(setup.stencil, c, mesh.points, face_base, setup.loop_face);
}

void Context::refresh_foam(std::span<const std::uint32_t> cells) {
  if (!setup.params.foam_gate) return;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 64), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      foam_ok[cells[i]] = foam_cell_ok(setup.stencil, cells[i], mesh.points, face_base, setup.loop_face);
  });
}

std::size_t Context::foam_failing() const {
  return static_cast<std::size_t>(std::count(foam_ok.begin(), foam_ok.end(), 0));
}

namespace {

// The repair's steps (repair_foam): the first length, relative to the local
// length cbrt(mean V0 of p's cells), and the halvings tried per direction.
constexpr double kRepairStep = 0.25;
constexpr int kRepairHalvings = 8;
constexpr int kRepairRounds = 20;
// The work bound, in passes over every point's cells (cells evaluated by
// the violation): the repair's time grows with the mesh and nothing else.
constexpr double kRepairBudget = 120;

// The summed OpenFOAM violation of the failing cells among `cells`; adds
// the cells evaluated to *work.
double violation(const Context& ctx, std::span<const std::uint32_t> cells, std::uint64_t* work) {
  *work += cells.size();
  double v = 0;
  for (std::uint32_t c : cells)
    if (!ctx.foam_ok[c]) v += foam_cell_violation(ctx.setup.stencil, c, ctx.mesh.points, ctx.face_base, ctx.setup.loop_face);
  return v;
}

// Exact: every valid cell among `cells` stays valid (the star test).
bool keeps_valid(const Context& ctx, std::span<const std::uint32_t> cells, std::vector<Point3>& scratch) {
  for (std::uint32_t c : cells)
    if (ctx.cell_valid[c] && !star_shaped_verdict(ctx.setup.stencil, c, ctx.mesh.points, true, scratch).valid) return false;
  return true;
}

// Tries p at x (projected on its primitive when k < 3): accepted, and
// committed, if the failing cells' violation drops below v0, the star test
// keeps the valid cells valid (exact) and both gates accept.
bool try_repair_move(Context& ctx, PointId p, int k, Point3 x, double v0, std::vector<double>& q,
                     std::vector<Point3>& scratch, std::uint64_t* work) {
  const auto cells = ctx.setup.stencil.cells_of(p);
  std::uint32_t prim = BoundaryConstraints::kNone;
  if (k < 3) x = ctx.bc->project(p, x, &prim);
  Point3& slot = ctx.mesh.points[p.idx];
  const Point3 o = slot;
  slot = x;
  if (violation(ctx, cells, work) < v0 && keeps_valid(ctx, cells, scratch) && ctx.gates_accept(cells, q)) {
    if (k < 3) ctx.bc->commit(p, prim);
    ctx.gates_commit(cells, q);
    for (std::uint32_t c : cells)
      if (!ctx.cell_valid[c]) ctx.cell_valid[c] = star_shaped_verdict(ctx.setup.stencil, c, ctx.mesh.points, true, scratch).valid;
    ctx.touched[p.idx] = 1;
    return true;
  }
  slot = o;
  return false;
}

// One move of p that lowers the violation of its failing cells: along the
// violation's negative forward-difference gradient, then along +- each
// tangent direction, from kRepairStep x the local length, halving. Returns
// whether p moved.
bool repair_point(Context& ctx, PointId p, std::vector<double>& q, std::vector<Point3>& scratch,
                  std::uint64_t* work) {
  const int k = ctx.setup.dof[p.idx];
  if (k == 0) return false;
  if (ctx.bc) ctx.bc->ensure(p);
  const auto cells = ctx.setup.stencil.cells_of(p);
  const double v0 = violation(ctx, cells, work);
  if (!(v0 > 0)) return false;
  double vol = 0;
  for (std::uint32_t c : cells) vol += ctx.setup.V0[c];
  const double ell = std::cbrt(vol / static_cast<double>(cells.size()));
  Vec3 B[3];
  ctx.basis(p, B);
  Point3& slot = ctx.mesh.points[p.idx];
  const Point3 o = slot;
  Vec3 g;  // in space: sum of g_i B_i (a direction, not a decision)
  const double h = 1e-4 * ell;
  for (int i = 0; i < k; ++i) {
    slot = o + h * B[i];
    g += ((violation(ctx, cells, work) - v0) / h) * B[i];
  }
  slot = o;
  const double gn = norm(g);
  double len = kRepairStep * ell;
  for (int hv = 0; hv <= kRepairHalvings; ++hv, len *= 0.5) {
    if (gn > 0 && try_repair_move(ctx, p, k, o - (len / gn) * g, v0, q, scratch, work)) return true;
    for (int d = 0; d < 2 * k; ++d)
      if (try_repair_move(ctx, p, k, o + ((d & 1) ? -len : len) * B[d / 2], v0, q, scratch, work)) return true;
  }
  return false;
}

}  // namespace

IterationRecord repair_foam(Context& ctx) {
  IterationRecord counts;
  if (!ctx.setup.params.foam_gate) return counts;
  std::vector<double> q;
  std::vector<Point3> scratch;
  std::vector<std::uint32_t> failing;
  ctx.foam_active = true;
  std::uint64_t work = 0;
  const double budget = kRepairBudget * static_cast<double>(ctx.setup.stencil.point_cells.size());
  for (int round = 0; round < kRepairRounds; ++round) {
    // A new base where one passes with both centres now, then every verdict.
    choose_foam_bases(ctx.mesh, ctx.setup.stencil, ctx.mesh.points, ctx.face_base);
    std::vector<std::uint32_t> all(ctx.setup.stencil.num_cells());
    for (std::uint32_t c = 0; c < all.size(); ++c) all[c] = c;
    ctx.refresh_foam(all);
    failing.clear();
    for (std::uint32_t c = 0; c < ctx.foam_ok.size(); ++c)
      if (!ctx.foam_ok[c]) failing.push_back(c);
    if (failing.empty()) break;
    std::uint64_t moved = 0;
    for (std::uint32_t c : failing)
      for (PointId p : ctx.setup.stencil.points_of(c)) {
        if (ctx.foam_ok[c] || static_cast<double>(work) > budget) break;
        ++counts.visited;
        moved += repair_point(ctx, p, q, scratch, &work);
      }
    counts.updates += moved;
    if (moved == 0) break;
  }
  return counts;
}

void list_worst_cells(const Context& ctx, OptimReport& rep) {
  std::vector<std::pair<double, std::uint32_t>> above;
  for (std::uint32_t c = 0; c < ctx.cell_quality.size(); ++c)
    if (!(ctx.cell_quality[c] <= OptimReport::kWorstBound)) above.push_back({ctx.cell_quality[c], c});
  rep.cells_above_bound = above.size();
  std::sort(above.begin(), above.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  if (above.size() > OptimReport::kMaxWorstCells) above.resize(OptimReport::kMaxWorstCells);
  for (const auto& [quality, c] : above) {
    WorstCell w;
    w.cell = c;
    w.quality = quality;
    for (PointId p : ctx.setup.stencil.points_of(c)) {
      const int dof = ctx.setup.dof[p.idx];
      if (dof == 0) w.pinned.push_back({p, ctx.mesh.point_class[p.idx]});
      w.on_edges += dof == 1;
      w.on_faces += dof == 2;
    }
    rep.worst_cells.push_back(std::move(w));
  }
}

}  // namespace polydual::optim_detail
