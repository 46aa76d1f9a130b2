// The global scheme (design §7): the same objective over all free point coordinates
// at once, minimised by Ceres.
//
// Why Ceres' GradientProblem + L-BFGS and not least squares on sqrt(kappa_mod):
// the objective is a plain sum of corner terms whose curvature is dominated by
// the terms themselves near tangled corners (kappa_mod grows like |V| S / V0^2
// there), so a Gauss-Newton model of sqrt(kappa_mod) residuals is poor exactly
// where untangling happens, and its Jacobian (dozens of points per corner through
// F and R) is costly. L-BFGS needs only the gradient, which we have analytically
// (reverse mode through F and R, objective.cpp).
//
// Constraints. Boundary points are parametrised in their local tangent frames
// (x = o + B t, t in R^k, k = 1 or 2); rather than a ceres::Manifold per point
// (whose Plus would have to walk the facetisation inside the line search, with
// no way to re-centre frames), we solve in rounds: each round runs L-BFGS for a
// fixed number of iterations from t = 0, then projects boundary points onto the
// facetisation (walking, boundary.h) and re-centres their frames. Validity: a
// round's move x = project(o + alpha B t) is checked cell by cell (exact
// test); the points of every cell that was valid before the round and is not
// now are frozen (put back where the round started) and the cells around them
// re-checked, until no valid cell is invalid: one bad region no longer throws
// away the whole round's progress. The move is then damped by halving alpha
// (the freezing redone) while the objective increased; if no alpha works the
// run stops. So, like the local scheme, the global scheme never turns a valid
// cell invalid. It stops on the local scheme's criterion, a relative decrease
// of the objective below tol after a round (the local: after a sweep).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lbfgs/lbfgs_module.h"
#include "optim/context.h"
#include "optim/objective.h"
#include "quality/star_verdict.h"

namespace polydual::optim_detail {
namespace {

struct Frames {
  std::vector<PointId> free;        // points with dof > 0, increasing
  std::vector<std::uint32_t> off;   // parameter offset of free[i]; off.back() = total
  std::vector<Point3> origin;
  std::vector<std::array<Vec3, 3>> basis;
};

class GlobalObjective {
 public:
  GlobalObjective(const Context& ctx, const Frames& fr) : ctx_(ctx), fr_(fr), pts_(ctx.mesh.points) {
    const MeshStencil& s = ctx.setup.stencil;
    cell_grad_.resize(s.cell_pts.size());
    energy_.resize(s.num_cells());
    // For each point the slots of cell_grad_ holding its per-cell gradients.
    slot_off_.assign(ctx.mesh.num_points() + 1, 0);
    for (PointId p : s.cell_pts) ++slot_off_[p.idx + 1];
    for (std::size_t p = 0; p + 1 < slot_off_.size(); ++p) slot_off_[p + 1] += slot_off_[p];
    slots_.resize(s.cell_pts.size());
    std::vector<std::uint32_t> fill(slot_off_.begin(), slot_off_.end() - 1);
    for (std::uint32_t i = 0; i < s.cell_pts.size(); ++i) slots_[fill[s.cell_pts[i].idx]++] = i;
  }
  // The callback of lbfgs_module::Problem.
  static bool evaluate(void* self, const double* t, double* cost, double* gradient) {
    return static_cast<const GlobalObjective*>(self)->Evaluate(t, cost, gradient);
  }
  bool Evaluate(const double* t, double* cost, double* gradient) const {
    for (std::size_t i = 0; i < fr_.free.size(); ++i) {
      Point3 x = fr_.origin[i];
      for (std::uint32_t j = fr_.off[i]; j < fr_.off[i + 1]; ++j) x += t[j] * fr_.basis[i][j - fr_.off[i]];
      pts_[fr_.free[i].idx] = x;
    }
    const MeshStencil& s = ctx_.setup.stencil;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.num_cells(), 128), [&](const auto& r) {
      for (std::size_t c = r.begin(); c != r.end(); ++c)
        energy_[c] = cell_energy_gradient(s, static_cast<std::uint32_t>(c), ctx_.setup.params.metric, pts_,
                                          ctx_.setup.V0[c], ctx_.setup.params.c,
                                          gradient ? cell_grad_.data() + s.cell_pt_off[c] : nullptr);
    });
    double sum = 0;  // serial: deterministic
    for (double e : energy_) sum += e;
    *cost = sum;
    if (gradient) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, fr_.free.size(), 512), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const PointId p = fr_.free[i];
          Vec3 g{};
          for (std::uint32_t a = slot_off_[p.idx]; a < slot_off_[p.idx + 1]; ++a) g += cell_grad_[slots_[a]];
          for (std::uint32_t j = fr_.off[i]; j < fr_.off[i + 1]; ++j)
            gradient[j] = dot(g, fr_.basis[i][j - fr_.off[i]]);
        }
      });
    }
    return std::isfinite(sum);
  }

 private:
  const Context& ctx_;
  const Frames& fr_;
  mutable std::vector<Point3> pts_;
  mutable std::vector<Vec3> cell_grad_;
  mutable std::vector<double> energy_;
  std::vector<std::uint32_t> slot_off_, slots_;
};

}  // namespace

namespace {

// Point -> cells (CSR over the stencil's cell points).
struct PointCells {
  std::vector<std::uint32_t> off, cells;
  explicit PointCells(const MeshStencil& s, std::size_t num_points) : off(num_points + 1, 0) {
    for (PointId p : s.cell_pts) ++off[p.idx + 1];
    for (std::size_t p = 0; p < num_points; ++p) off[p + 1] += off[p];
    cells.resize(s.cell_pts.size());
    std::vector<std::uint32_t> fill(off.begin(), off.end() - 1);
    for (std::uint32_t c = 0; c < s.num_cells(); ++c)
      for (PointId p : s.points_of(c)) cells[fill[p.idx]++] = c;
  }
};

// Exact star verdict of the given cells into valid_now.
void check_cells(Context& ctx, const std::vector<std::uint32_t>& cells, std::vector<std::uint8_t>& valid_now) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 256), [&](const auto& r) {
    std::vector<Point3> scratch;
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      valid_now[cells[i]] = star_shaped_verdict(ctx.setup.stencil, cells[i], ctx.mesh.points, true, scratch).valid;
  });
}

// Puts back (to `before`) every point of the cells that were valid and are not
// now, re-checks the cells around them, and repeats until no valid cell is
// invalid (at the latest when all their points are back: those cells are then
// as before the round). Serial decisions over sorted lists: deterministic.
// Returns the number of points frozen.
std::size_t freeze_invalidating_points(Context& ctx, const PointCells& pc, const std::vector<Point3>& before,
                                       std::vector<std::uint8_t>& valid_now, std::vector<std::uint8_t>& frozen) {
  const std::size_t nc = ctx.mesh.num_cells();
  std::vector<std::uint32_t> bad;
  for (std::uint32_t c = 0; c < nc; ++c)
    if (ctx.cell_valid[c] && !valid_now[c]) bad.push_back(c);
  std::size_t count = 0;
  std::vector<std::uint32_t> recheck;
  std::vector<std::uint8_t> mark(nc, 0);
  while (!bad.empty()) {
    recheck.clear();
    for (std::uint32_t c : bad)
      for (PointId p : ctx.setup.stencil.points_of(c)) {
        if (frozen[p.idx] || ctx.mesh.points[p.idx] == before[p.idx]) continue;
        frozen[p.idx] = 1;
        ++count;
        ctx.mesh.points[p.idx] = before[p.idx];
        for (std::uint32_t a = pc.off[p.idx]; a < pc.off[p.idx + 1]; ++a)
          if (!mark[pc.cells[a]]) { mark[pc.cells[a]] = 1; recheck.push_back(pc.cells[a]); }
      }
    std::sort(recheck.begin(), recheck.end());
    check_cells(ctx, recheck, valid_now);
    bad.clear();
    for (std::uint32_t c : recheck) {
      mark[c] = 0;
      if (ctx.cell_valid[c] && !valid_now[c]) bad.push_back(c);
    }
  }
  return count;
}

// One L-BFGS solve of the round from t = 0 (lbfgs/lbfgs_module.h: Ceres'
// GradientProblemSolver, linked in or loaded as a module).
std::vector<double> solve_round(const Context& ctx, const Frames& fr) {
  std::vector<double> t(fr.off.back(), 0.0);
  GlobalObjective objective(ctx, fr);
  const lbfgs_module::Problem problem{t.size(), &objective, &GlobalObjective::evaluate};
  lbfgs_module::Options opt;
  opt.max_iterations = ctx.setup.params.global_iterations_per_round;
  opt.function_tolerance = 1e-12;
  opt.parameter_tolerance = 1e-12;
  std::string error;
  if (!lbfgs_module::lbfgs_api().minimize(problem, opt, t.data(), error))
    throw std::runtime_error("the global optimiser's L-BFGS solver failed: " + error);
  return t;
}

// Places every free point at project(o + alpha B t), its primitive into prim.
void place_points(Context& ctx, const Frames& fr, const std::vector<double>& t, double alpha,
                  std::vector<std::uint32_t>& prim) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, fr.free.size(), 512), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const PointId p = fr.free[i];
      Point3 x = fr.origin[i];
      for (std::uint32_t j = fr.off[i]; j < fr.off[i + 1]; ++j) x += (alpha * t[j]) * fr.basis[i][j - fr.off[i]];
      if (ctx.setup.dof[p.idx] < 3) x = ctx.bc->project(p, x, &prim[i]);
      ctx.mesh.points[p.idx] = x;
    }
  });
}

}  // namespace

void run_global(Context& ctx) {
  const auto& prm = ctx.setup.params;
  Frames fr;
  fr.off.push_back(0);
  for (std::size_t i = 0; i < ctx.mesh.num_points(); ++i)
    if (ctx.setup.dof[i] > 0) {
      fr.free.push_back(PointId(i));
      fr.off.push_back(fr.off.back() + ctx.setup.dof[i]);
    }
  if (fr.free.empty()) return;
  fr.origin.resize(fr.free.size());
  fr.basis.resize(fr.free.size());
  const std::size_t nc = ctx.mesh.num_cells();
  const PointCells pc(ctx.setup.stencil, ctx.mesh.num_points());
  std::vector<std::uint32_t> all_cells(nc);
  for (std::uint32_t c = 0; c < nc; ++c) all_cells[c] = c;
  std::vector<Point3> before;
  std::vector<std::uint32_t> prim(fr.free.size());
  std::vector<std::uint8_t> valid_now(nc), frozen(ctx.mesh.num_points());
  double f_prev = ctx.report->iterations.back().objective;
  for (int round = 1; round <= prm.max_iter; ++round) {
    for (std::size_t i = 0; i < fr.free.size(); ++i) {
      fr.origin[i] = ctx.mesh.points[fr.free[i].idx];
      ctx.basis(fr.free[i], fr.basis[i].data());
    }
    const std::vector<double> t = solve_round(ctx, fr);
    // Projected move, points of newly invalid cells frozen, damped on an increase.
    before = ctx.mesh.points;
    bool accepted = false;
    double alpha = 1.0;
    for (int hv = 0; hv <= prm.max_halvings && !accepted; ++hv, alpha *= 0.5) {
      place_points(ctx, fr, t, alpha, prim);
      std::fill(frozen.begin(), frozen.end(), 0);
      check_cells(ctx, all_cells, valid_now);
      freeze_invalidating_points(ctx, pc, before, valid_now, frozen);
      accepted = ctx.mesh.points != before && ctx.objective(ctx.mesh.points) <= f_prev;
    }
    if (!accepted) {
      ctx.mesh.points = before;
      break;
    }
    for (std::size_t i = 0; i < fr.free.size(); ++i) {
      const PointId p = fr.free[i];
      if (frozen[p.idx]) continue;
      if (ctx.setup.dof[p.idx] < 3) ctx.bc->commit(p, prim[i]);
      if (!(ctx.mesh.points[p.idx] == before[p.idx])) ++ctx.report->vertex_updates;
    }
    ctx.cell_valid = valid_now;
    ctx.all_touched = true;  // a round moves every free point
    ctx.record(round);
    const double f = ctx.report->iterations.back().objective;
    if (std::fabs(f_prev - f) < prm.effective_tol() * std::fabs(f_prev)) break;
    f_prev = f;
  }
}

}  // namespace polydual::optim_detail
