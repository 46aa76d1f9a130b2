// The paper's local scheme (3.3): Gauss-Seidel sweeps; at each free point, Newton
// on grad f = 0 for the local objective, in the point's local parametric space
// (R^3 inside, the tangent plane/line of its current primitive on the boundary).
// Sweeps visit colour classes of independent points in parallel (deterministic
// for any thread count) and an active set; proofs/quality.md §6-7.
#include <ceres/jet.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include <array>
#include <optional>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "optim/context.h"
#include "optim/lagged_objective.h"
#include "optim/objective.h"
#include "optim/planarity.h"
#include "quality/star_verdict.h"

namespace polydual::optim_detail {
namespace {

// Fixed 3x3 systems; a point with k < 3 dof pads the unused rows with the
// identity and a zero gradient, so its step has zeros there.
using Mat = Eigen::Matrix3d;
using Vec = Eigen::Vector3d;
using Jet3 = ceres::Jet<double, 3>;

class VertexNewton {
 public:
  explicit VertexNewton(Context& ctx) : ctx_(ctx) {}

  // Up to params.newton_steps Newton steps at p; returns the number accepted and
  // the total displacement in *moved.
  int optimise(PointId p, const SweepMode& mode, double* moved) {
    const auto& prm = ctx_.setup.params;
    Point3* pts = ctx_.mesh.points.data();
    const LocalObjective obj{ctx_.setup.stencil, pts, ctx_.setup.V0.data(), prm.metric, prm.c, p};
    const int k = ctx_.setup.dof[p.idx];
    const auto cells = ctx_.setup.stencil.cells_of(p);
    double v0 = 0;
    for (std::uint32_t c : cells) v0 += ctx_.setup.V0[c];
    const double ell = std::cbrt(v0 / static_cast<double>(cells.size()));  // local length
    const double h = prm.fd_step * ell;
    int accepted = 0;
    *moved = 0;
    ctx_.touched[p.idx] = 1;  // this visit may write p (its own flag: no other thread's)
    if (ctx_.bc) ctx_.bc->ensure(p);  // its initial primitive, before any move (lazy constraints)
    for (int step = 0; step < prm.newton_steps; ++step) {
      const Point3 o = pts[p.idx];
      Vec3 B[3];
      ctx_.basis(p, B);
      // f in the local parametric space: x(t) = o + B t (t in R^k).
      auto x_of = [&](const double* t) {
        Point3 x = o;
        for (int i = 0; i < k; ++i) x += t[i] * B[i];
        return x;
      };
      const OptimParams::Derivatives der = der_ = model_of(cells, mode);
      const bool corrected = der == OptimParams::Derivatives::Corrected;
      const bool lagged = der == OptimParams::Derivatives::Lagged || corrected;
      if (lagged)
        lagged_.build(ctx_.setup.stencil, pts, ctx_.setup.V0.data(), prm.metric, p, corrected ? ctx_.grad_R.data() : nullptr,
                      corrected ? ctx_.grad_F.data() : nullptr);
      // Face flatness (optim/planarity.h), weighted by prm.planarity: added to
      // the value, and its derivatives by central differences to g and H.
      const bool flat = prm.planarity > 0;
      if (flat) planarity_.build(ctx_.setup.stencil, p);
      auto eval = [&](const Point3& x) {
        const double e = flat ? prm.planarity * planarity_.value(ctx_.setup.stencil, pts, x) : 0.0;
        if (lagged) return lagged_.value(x, prm.c) + e;
        const double xa[3] = {x.x, x.y, x.z};
        return obj(xa) + e;
      };
      auto f = [&](const double* t) { return eval(x_of(t)); };
      Vec g = Vec::Zero();
      Mat H = Mat::Identity();
      const double f0 = derivatives(p, o, B, k, h, obj, x_of, f, g, H);
      if (!g.allFinite() || !H.allFinite()) break;
      if (g.norm() * ell <= 1e-12 * std::fabs(f0)) break;  // stationary
      Vec d = positive_definite_solve_k(H, g, k);
      // Cap the step at the local length: Newton on a tangled configuration can
      // propose jumps far outside the local model's validity.
      const double dn = d.norm();
      if (dn > ell) d *= ell / dn;
      const double slope = g.dot(d);
      if (!(slope < 0)) break;
      if (-slope <= 1e-14 * std::fabs(f0)) break;  // Newton decrement ~ 0: converged
      std::uint32_t prim = BoundaryConstraints::kNone;
      Point3 xt = o;
      if (!damped_step(p, o, k, d, f0, slope, mode.omega, x_of, eval, cells, xt, prim)) break;
      if (k < 3) ctx_.bc->commit(p, prim);  // re-centre the parametric space
      ctx_.gates_commit(cells, q_);
      for (std::uint32_t c : cells)
        if (!ctx_.cell_valid[c])
          ctx_.cell_valid[c] = star_shaped_verdict(ctx_.setup.stencil, c, ctx_.mesh.points, true, scratch_).valid;
      ++accepted;
      const double disp = norm(xt - o);
      *moved += disp;
      if (disp <= 1e-10 * ell) break;
    }
    return accepted;
  }

  // f0, g and H at o (t = 0) in the parametric space x_of, by the visit's
  // model der_ (analytic, lagged or corrected: closed form; finite
  // differences of f; ceres::Jet of obj), with the planarity term's share.
  template <class X, class F>
  double derivatives(PointId p, const Point3& o, const Vec3* B, int k, double h, const LocalObjective& obj,
                     const X& x_of, const F& f, Vec& g, Mat& H) {
    const auto& prm = ctx_.setup.params;
    const bool flat = prm.planarity > 0;
    const bool lagged =
        der_ == OptimParams::Derivatives::Lagged || der_ == OptimParams::Derivatives::Corrected;
    double f0;
    if (der_ == OptimParams::Derivatives::Analytic || lagged) {
      f0 = analytic_derivatives(p, B, k, g, H);
      if (flat) add_planarity(x_of, k, h, prm.planarity, f0, g, H);
    } else if (der_ == OptimParams::Derivatives::FiniteDifference) {
      const double zero[3] = {0, 0, 0};
      f0 = f(zero);  // the planarity term is in f already
      fd_derivatives(f, k, h, f0, g, H);
    } else {
      const double xo[3] = {o.x, o.y, o.z};
      f0 = obj(xo);  // kappa alone: add_planarity adds the term and its derivatives
      exact_derivatives(obj, o, B, k, h, g, H);
      if (flat) add_planarity(x_of, k, h, prm.planarity, f0, g, H);
    }
    return f0;
  }

  // Damping (paper 3.3 / [9]): halve until Armijo holds AND every incident
  // cell that was valid is still valid (exact star test). Over-relaxation
  // (omega > 1 in smoothing sweeps): omega x the Newton step is tried
  // first, then the undamped step and its halvings. On success p is at xt
  // (prim: its boundary primitive there); otherwise p is back at o.
  template <class X, class E>
  bool damped_step(PointId p, const Point3& o, int k, const Vec& d, double f0, double slope, double omega,
                   const X& x_of, const E& eval, std::span<const std::uint32_t> cells, Point3& xt,
                   std::uint32_t& prim) {
    Point3* pts = ctx_.mesh.points.data();
    const bool over = omega > 1.0;
    double alpha = over ? omega : 1.0;
    bool ok = false;
    for (int hv = over ? -1 : 0; hv <= ctx_.setup.params.max_halvings && !ok; ++hv, alpha = hv <= 0 ? 1.0 : alpha * 0.5) {
      double t[3] = {0, 0, 0};
      for (int i = 0; i < k; ++i) t[i] = alpha * d[i];
      xt = x_of(t);
      if (k < 3) xt = ctx_.bc->project(p, xt, &prim);
      const double ft = eval(xt);
      if (!(ft <= f0 + 1e-4 * alpha * slope)) continue;
      pts[p.idx] = xt;
      // Exact: the star test; then the floating-point gates (context.h).
      ok = keeps_valid(cells) && ctx_.gates_accept(cells, q_);
      if (!ok) pts[p.idx] = o;
    }
    return ok;
  }

  // Whether the last visit used the full analytic model (Corrected runs:
  // model_of), for the sweep's counts.
  bool used_full_model() const { return der_ == OptimParams::Derivatives::Analytic; }

 private:
  // The sweep's model, except that a point of a cell whose quality (at the last
  // record) is above mode.full_model_above gets the full analytic model: the
  // corrected lagged model is first-order in the centres, which does not
  // recover poorly shaped cells (on a mesh just untangled its max quality
  // oscillates), while the full model does; such points are few.
  OptimParams::Derivatives model_of(std::span<const std::uint32_t> cells, const SweepMode& mode) const {
    const OptimParams::Derivatives d = ctx_.setup.params.derivatives;
    if (d != OptimParams::Derivatives::Corrected) return d;
    if (mode.untangling == SweepMode::Untangling::Lagged) return OptimParams::Derivatives::Lagged;
    if (mode.untangling == SweepMode::Untangling::FullWhereInvalid) {
      for (std::uint32_t c : cells)
        if (!ctx_.cell_valid[c]) return OptimParams::Derivatives::Analytic;
      return OptimParams::Derivatives::Lagged;
    }
    for (std::uint32_t c : cells)
      if (!(ctx_.cell_quality[c] <= mode.full_model_above)) return OptimParams::Derivatives::Analytic;
    return d;
  }

  bool keeps_valid(std::span<const std::uint32_t> cells) {
    for (std::uint32_t c : cells)
      if (ctx_.cell_valid[c] &&
          !star_shaped_verdict(ctx_.setup.stencil, c, ctx_.mesh.points, true, scratch_).valid)
        return false;
    return true;
  }

  // Analytic gradient and Hessian in x (local_objective_derivatives), projected
  // on the parametric space: g_t = B^T g, H_t = B^T H B (x = o + B t is affine).
  double analytic_derivatives(PointId p, const Vec3* B, int k, Vec& g, Mat& H) const {
    const auto& prm = ctx_.setup.params;
    double gx[3], Hx[9];
    const bool lagged = der_ == OptimParams::Derivatives::Lagged || der_ == OptimParams::Derivatives::Corrected;
    const double f0 = lagged
                          ? lagged_.derivatives(ctx_.mesh.points[p.idx], prm.c, gx, Hx)
                          : local_objective_derivatives(ctx_.setup.stencil, ctx_.mesh.points.data(), ctx_.setup.V0.data(),
                                                        prm.metric, prm.c, p, gx, Hx);
    Vec3 HB[3];
    for (int i = 0; i < k; ++i)
      for (int r = 0; r < 3; ++r) HB[i][r] = Hx[3 * r] * B[i][0] + Hx[3 * r + 1] * B[i][1] + Hx[3 * r + 2] * B[i][2];
    for (int i = 0; i < k; ++i) {
      g[i] = B[i][0] * gx[0] + B[i][1] * gx[1] + B[i][2] * gx[2];
      for (int j = 0; j < k; ++j) H(i, j) = dot(B[i], HB[j]);
    }
    return f0;
  }

  // f0, g, H += w x (the planarity term, its central-difference derivatives).
  template <class X>
  void add_planarity(const X& x_of, int k, double h, double w, double& f0, Vec& g, Mat& H) const {
    const Point3* pts = ctx_.mesh.points.data();
    auto e = [&](const double* t) { return planarity_.value(ctx_.setup.stencil, pts, x_of(t)); };
    const double zero[3] = {0, 0, 0};
    const double e0 = e(zero);
    Vec ge = Vec::Zero();
    Mat he = Mat::Zero();
    fd_derivatives(e, k, h, e0, ge, he);
    f0 += w * e0;
    for (int i = 0; i < k; ++i) {
      g[i] += w * ge[i];
      for (int j = 0; j < k; ++j) H(i, j) += w * he(i, j);
    }
  }

  // Central differences (the paper): g_i = (f+i - f-i)/2h, H_ii = (f+i - 2f0 + f-i)/h^2,
  // H_ij = (f(+i+j) - f+i - f+j + 2f0 - f-i - f-j + f(-i-j)) / 2h^2: 1 + 2k + k(k-1) evaluations.
  template <class F>
  static void fd_derivatives(F& f, int k, double h, double f0, Vec& g, Mat& H) {
    double fp[3], fm[3];
    for (int i = 0; i < k; ++i) {
      double t[3] = {0, 0, 0};
      t[i] = h; fp[i] = f(t);
      t[i] = -h; fm[i] = f(t);
      g[i] = (fp[i] - fm[i]) / (2 * h);
      H(i, i) = (fp[i] - 2 * f0 + fm[i]) / (h * h);
    }
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j) {
        double t[3] = {0, 0, 0};
        t[i] = h; t[j] = h;
        const double fpp = f(t);
        t[i] = -h; t[j] = -h;
        const double fmm = f(t);
        H(i, j) = H(j, i) = (fpp - fp[i] - fp[j] + 2 * f0 - fm[i] - fm[j] + fmm) / (2 * h * h);
      }
  }

  // Exact gradient by ceres::Jet; Hessian by central differences of the exact
  // gradient (symmetrised). Nested Jets would give an exact Hessian but Ceres'
  // Jet does not mix with double constants at the inner level.
  static void exact_gradient(const LocalObjective& obj, const Point3& o, const Vec3* B, int k,
                             const double* t, double* g, double* value) {
    Jet3 x[3];
    for (int d = 0; d < 3; ++d) x[d] = Jet3(o[d]);
    for (int i = 0; i < k; ++i) {
      const Jet3 ti(t[i], i);
      for (int d = 0; d < 3; ++d) x[d] += ti * B[i][d];
    }
    const Jet3 fx = obj(x);
    for (int i = 0; i < k; ++i) g[i] = fx.v[i];
    if (value) *value = fx.a;
  }
  static void exact_derivatives(const LocalObjective& obj, const Point3& o, const Vec3* B, int k,
                                double h, Vec& g, Mat& H) {
    double t[3] = {0, 0, 0}, gp[3], gm[3], g0[3];
    exact_gradient(obj, o, B, k, t, g0, nullptr);
    for (int i = 0; i < k; ++i) g[i] = g0[i];
    for (int i = 0; i < k; ++i) {
      t[i] = h; exact_gradient(obj, o, B, k, t, gp, nullptr);
      t[i] = -h; exact_gradient(obj, o, B, k, t, gm, nullptr);
      t[i] = 0;
      for (int j = 0; j < k; ++j) H(j, i) = (gp[j] - gm[j]) / (2 * h);
    }
    const Mat Ht = H.transpose();
    H = 0.5 * (H + Ht);
  }

  // Solve (H + tau I) d = -g, doubling tau from a small multiple of the
  // diagonal's scale until Cholesky succeeds (paper 3.3, [9] Nocedal-Wright 3.4).
  static Vec positive_definite_solve_k(const Mat& H, const Vec& g, int k) {
    double scale = 0;
    for (int i = 0; i < k; ++i) scale = std::max(scale, std::fabs(H(i, i)));
    if (!(scale > 0)) scale = 1;
    double tau = 0;
    for (int it = 0; it < 80; ++it) {
      Mat M = H;
      for (int i = 0; i < k; ++i) M(i, i) += tau;
      const Eigen::LLT<Mat> llt(M);
      if (llt.info() == Eigen::Success) {
        // LLT succeeds on some indefinite matrices with tiny pivots: also require
        // positive pivots relative to the scale.
        const Mat Lm = llt.matrixL();
        bool good = true;
        for (int i = 0; i < k; ++i) good = good && Lm(i, i) > 1e-8 * std::sqrt(scale);
        if (good) return llt.solve(-g);
      }
      tau = tau == 0 ? 1e-3 * scale : 2 * tau;
    }
    return -g / scale;  // steepest descent as a last resort
  }

  Context& ctx_;
  OptimParams::Derivatives der_ = OptimParams::Derivatives::Analytic;  // the current visit's model
  std::vector<Point3> scratch_;
  std::vector<double> q_;  // the gates' qualities of the cells of the point being moved
  LaggedObjective lagged_;  // rebuilt at every Newton step of a Lagged visit
  PlanarityTerm planarity_;  // the loops around the visited point (planarity > 0)
};

// Independent blocks for a parallel Gauss-Seidel: the points of one pass
// (surface or volume) are cut, in index order, into blocks of kBlockPoints
// consecutive points (the dual's points follow the tets' spatial order, so a
// block is a compact piece of the mesh), and the blocks are greedily coloured
// in index order so that no cell holds points of two blocks of one colour.
// A block's points are visited one after the other in index order (a plain
// Gauss-Seidel, whose working set stays in cache); the blocks of one colour
// run in parallel. A point's update reads and writes only its own cells
// (positions of their points, validity flags, change stamps) and its own
// boundary primitive, so the blocks of one colour never touch the same data
// and the result is that of visiting them one by one in any order: it depends
// on the blocks and their colours only, never on the thread count or the
// scheduling (proofs/quality.md §7).
constexpr std::uint32_t kBlockPoints = 256;

struct ColourClasses {
  std::vector<std::uint32_t> points;      // by colour, then block; increasing within a block
  std::vector<std::uint32_t> block_off{0};   // block b is points[block_off[b] .. block_off[b+1])
  std::vector<std::uint32_t> colour_off{0};  // colour c is blocks [colour_off[c], colour_off[c+1])
};

// only (null: every point): colour the listed points only, and the cells
// around them (an untangling sweep's candidates; smaller blocks keep the few
// candidates spread over both threads).
constexpr std::uint32_t kSubsetBlockPoints = 32;
// block: one entry per point, kNone on entry and on return (kept by the
// caller: an untangling sweep colours a few points of a large mesh).
constexpr std::uint32_t kNoBlock = UINT32_MAX;
ColourClasses colour_points(const Context& ctx, bool surface, const std::vector<char>* only,
                            std::vector<std::uint32_t>& block) {
  const std::size_t np = ctx.mesh.num_points();
  constexpr std::uint32_t kNone = kNoBlock;
  const std::uint32_t block_points = only ? kSubsetBlockPoints : kBlockPoints;
  // Blocks of consecutive eligible points.
  std::vector<std::uint32_t> members;
  std::uint32_t nb = 0, in_block = 0;
  for (std::size_t i = 0; i < np; ++i) {
    const int k = ctx.setup.dof[i];
    if (k == 0 || surface != (k < 3) || (only && !(*only)[i])) continue;
    if (in_block == 0) ++nb;
    block[i] = nb - 1;
    members.push_back(static_cast<std::uint32_t>(i));
    in_block = (in_block + 1) % block_points;
  }
  // The cells that hold an eligible point (every cell without `only`; the
  // order does not matter: the colouring below only stamps).
  std::vector<std::uint32_t> cells;
  if (!only) {
    cells.resize(ctx.setup.stencil.num_cells());
    for (std::uint32_t c = 0; c < cells.size(); ++c) cells[c] = c;
  } else {
    std::vector<char> seen(ctx.setup.stencil.num_cells(), 0);
    for (std::uint32_t p : members)
      for (std::uint32_t c : ctx.setup.stencil.cells_of(PointId(p)))
        if (!seen[c]) { seen[c] = 1; cells.push_back(c); }
  }
  // Blocks sharing a cell are neighbours (a block may be listed more than
  // once: the colouring below only stamps them).
  std::vector<std::vector<std::uint32_t>> nbrs(nb);
  std::vector<std::uint32_t> in_cell, listed(nb, kNone);  // listed[b] == c: b already in c's list
  for (std::uint32_t c : cells) {
    in_cell.clear();
    for (PointId q : ctx.setup.stencil.points_of(c)) {
      const std::uint32_t b = block[q.idx];
      if (b != kNone && listed[b] != c) { listed[b] = c; in_cell.push_back(b); }
    }
    for (std::uint32_t a : in_cell)
      for (std::uint32_t b : in_cell)
        if (a != b) nbrs[a].push_back(b);
  }
  // Greedy colouring of the blocks in index order.
  std::vector<std::uint32_t> colour(nb, kNone), stamp;
  std::uint32_t ncolours = 0;
  for (std::uint32_t b = 0; b < nb; ++b) {
    for (std::uint32_t n : nbrs[b])
      if (colour[n] != kNone) stamp[colour[n]] = b + 1;
    std::uint32_t col = 0;
    while (col < ncolours && stamp[col] == b + 1) ++col;
    if (col == ncolours) { ++ncolours; stamp.push_back(0); }
    colour[b] = col;
  }
  // Blocks grouped by colour (increasing within a colour), points by block.
  ColourClasses cc;
  std::vector<std::uint32_t> order(nb);
  for (std::uint32_t b = 0; b < nb; ++b) order[b] = b;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return colour[a] < colour[b]; });
  std::vector<std::uint32_t> first(nb + 1, 0);  // block b's points in index order
  for (std::uint32_t i : members) ++first[block[i] + 1];
  for (std::uint32_t b = 0; b < nb; ++b) first[b + 1] += first[b];
  std::vector<std::uint32_t> by_block(first.back());
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::uint32_t i : members) by_block[fill[block[i]]++] = i;
  for (std::uint32_t i : members) block[i] = kNone;
  cc.colour_off.assign(ncolours + 1, 0);
  for (std::uint32_t b = 0; b < nb; ++b) ++cc.colour_off[colour[b] + 1];
  for (std::uint32_t c = 0; c < ncolours; ++c) cc.colour_off[c + 1] += cc.colour_off[c];
  for (std::uint32_t b : order) {
    cc.points.insert(cc.points.end(), by_block.begin() + first[b], by_block.begin() + first[b + 1]);
    cc.block_off.push_back(static_cast<std::uint32_t>(cc.points.size()));
  }
  return cc;
}

// Surface pass (model edges and faces), then volume pass (paper 3.3).
using Passes = std::array<ColourClasses, 2>;
Passes colour_passes(Context& ctx, std::vector<std::uint32_t>& block, const std::vector<char>* only = nullptr) {
  Passes p{colour_points(ctx, true, only, block), colour_points(ctx, false, only, block)};
  const auto n = static_cast<std::uint32_t>(p[0].colour_off.size() + p[1].colour_off.size() - 2);
  ctx.report->colours = std::max(ctx.report->colours, n);
  return p;
}

// One sweep: the surface pass then the volume pass, each colour in parallel,
// visiting the points for which active(p) holds, each as `mode` says. A point whose accepted moves
// add up to more than settle_move x its local length stamps its cells with
// `sweep` in last_change. Visits and accepted moves go to counts.
template <class Active>
void sweep_points(Context& ctx, const Passes& passes, tbb::enumerable_thread_specific<VertexNewton>& solvers,
                  const SweepMode& mode, int sweep, std::vector<int>& last_change, const Active& active,
                  IterationRecord& counts) {
  std::atomic<std::uint64_t> updates{0}, visited{0}, full{0};
  for (const ColourClasses& cc : passes) {
    for (std::size_t col = 0; col + 1 < cc.colour_off.size(); ++col) {
      const std::uint32_t b = cc.colour_off[col], e = cc.colour_off[col + 1];
      tbb::parallel_for(tbb::blocked_range<std::uint32_t>(b, e, 1), [&](const auto& r) {
        VertexNewton& solver = solvers.local();
        std::uint64_t n_upd = 0, n_vis = 0, n_full = 0;
        for (std::uint32_t a = cc.block_off[r.begin()]; a != cc.block_off[r.end()]; ++a) {
          const PointId p(cc.points[a]);
          if (!active(p)) continue;
          ++n_vis;
          double moved = 0;
          const int n = solver.optimise(p, mode, &moved);
          n_upd += static_cast<std::uint64_t>(n);
          n_full += solver.used_full_model();
          if (n == 0) continue;
          const auto cells = ctx.setup.stencil.cells_of(p);
          double v0 = 0;
          for (std::uint32_t c : cells) v0 += ctx.setup.V0[c];
          const double ell = std::cbrt(v0 / static_cast<double>(cells.size()));
          if (moved > ctx.setup.params.settle_move * ell)
            for (std::uint32_t c : cells) last_change[c] = sweep;
        }
        updates += n_upd;
        visited += n_vis;
        full += n_full;
      });
    }
  }
  counts.updates = updates;
  counts.visited = visited;
  counts.full_model = full;
}

// Records iteration `sweep` with the visit counts; returns the record.
IterationRecord& record_sweep(Context& ctx, int sweep, const IterationRecord& counts) {
  ctx.report->vertex_updates += counts.updates;
  ctx.record(sweep);
  IterationRecord& rec = ctx.report->iterations.back();
  rec.visited = counts.visited;
  rec.updates = counts.updates;
  rec.full_model = counts.full_model;
  return rec;
}

// Grows the marked cells by `reach` point-sharing layers.
void grow_layers(const Context& ctx, std::vector<char>& near, int reach) {
  std::vector<std::uint32_t> front, next;
  for (std::size_t c = 0; c < near.size(); ++c)
    if (near[c]) front.push_back(static_cast<std::uint32_t>(c));
  for (int layer = 0; layer < reach; ++layer) {
    next.clear();
    for (std::uint32_t c : front)
      for (PointId q : ctx.setup.stencil.points_of(c))
        for (std::uint32_t d : ctx.setup.stencil.cells_of(q))
          if (!near[d]) { near[d] = 1; next.push_back(d); }
    front.swap(next);
  }
}

// The polish phase (prm.polish_sweeps): sweeps that visit only the points of
// the cells whose quality is above mean + polish_share x (w - mean), w the
// current worst quality (the slowest cells of the Gauss-Seidel), and of their
// point-sharing neighbours
// (kPolishReach layers: a worst cell is held by the balance with its
// neighbours, which must make room for it to improve; without them the polish
// stalls after ~3 sweeps), while the worst quality drops by more than
// kPolishTol (relative). A polish sweep costs a few percent of a full one. A polish sweep after which the
// worst quality is not lower is undone (its points restored: every cell was
// valid before it, so every cell is valid again), so the polish never makes
// the worst cell worse. Only the cells around the polished points get their
// qualities and centre gradients refreshed; the phase ends with the min-max
// descent on the worst cells (worst_descent.cpp) and one record.
constexpr int kPolishReach = 1;
constexpr double kPolishTol = 1e-5;
// Corrected derivatives: from the second smoothing sweep on, the points of
// cells above kFullModelRatio x the mean quality use the full analytic model
// (VertexNewton::model_of); in the polish, the points of cells above
// mean + kPolishFullModelShare x (max - mean). The first smoothing sweep
// uses the corrected model everywhere: after the lagged untangling sweep it
// starts from a mild state, and the few cells it leaves badly shaped are
// what the later full-model visits and the polish repair (bench/HISTORY.md,
// "The full model where it pays").
constexpr double kFullModelRatio = 1.3;
constexpr double kPolishFullModelShare = 0.8;

void polish_worst(Context& ctx, const Passes& passes, tbb::enumerable_thread_specific<VertexNewton>& solvers,
                  SweepMode mode, int sweep, std::vector<int>& last_change) {
  const auto& prm = ctx.setup.params;
  const double mean = ctx.last_stats.mean;
  std::vector<char> bad(ctx.mesh.num_cells(), 0);
  std::vector<std::uint32_t> region;  // the cells of the points of bad cells
  std::vector<std::pair<std::uint32_t, Point3>> saved;
  IterationRecord counts;
  double worst = ctx.last_stats.max;
  int k = 0;
  while (k < prm.polish_sweeps && sweep + k < prm.max_iter) {
    // The bad cells follow the current worst (a fixed threshold leaves nothing
    // to polish once an outlier drops below it).
    const double threshold = mean + prm.polish_share * (worst - mean);
    for (std::size_t c = 0; c < bad.size(); ++c) bad[c] = char(ctx.cell_quality[c] > threshold);
    grow_layers(ctx, bad, kPolishReach);
    region.clear();
    saved.clear();
    for (std::size_t c = 0; c < bad.size(); ++c)
      if (bad[c])
        for (PointId q : ctx.setup.stencil.points_of(static_cast<std::uint32_t>(c))) {
          saved.emplace_back(q.idx, ctx.mesh.points[q.idx]);
          for (std::uint32_t d : ctx.setup.stencil.cells_of(q)) region.push_back(d);
        }
    if (saved.empty()) break;
    std::sort(region.begin(), region.end());
    region.erase(std::unique(region.begin(), region.end()), region.end());
    auto active = [&](PointId p) {
      for (std::uint32_t c : ctx.setup.stencil.cells_of(p))
        if (bad[c]) return true;
      return false;
    };
    IterationRecord one;
    mode.untangling = SweepMode::Untangling::None;
    mode.full_model_above = mean + kPolishFullModelShare * (worst - mean);
    sweep_points(ctx, passes, solvers, mode, sweep + ++k, last_change, active, one);
    counts.visited += one.visited;
    counts.updates += one.updates;
    counts.full_model += one.full_model;
    if (one.updates == 0) break;
    ctx.refresh_cells(region);
    const double w = *std::max_element(ctx.cell_quality.begin(), ctx.cell_quality.end());
    if (!(w < worst)) {
      for (const auto& [q, x] : saved) ctx.mesh.points[q] = x;
      ctx.refresh_cells(region);
      ctx.refresh_foam(region);
    }
    if (!(w < worst * (1 - kPolishTol))) break;
    worst = w;
  }
  if (k == 0) return;
  // The polish's last stage: min-max descent on the worst cells (in the same record).
  ctx.lap("iterations");
  const IterationRecord d = descend_worst(ctx);
  ctx.lap("worst_descent");
  counts.visited += d.visited;
  counts.updates += d.updates;
  record_sweep(ctx, sweep + k, counts);
}

// near[c]: cell c is within kUntangleReach point-sharing layers of a cell
// that is invalid now. The untangling rings grow only there, so that once few
// cells are left the sweeps visit their surroundings, not every region that
// moved before.
constexpr int kUntangleReach = 2;
// Untangling stops after kUntangleStall sweeps without fewer invalid cells
// (a cell wrapped around a sheet's free edge cannot be untangled by moving
// points: the split cuts it, see lib/split).
constexpr int kUntangleStall = 4;
void mark_near_invalid(const Context& ctx, std::vector<char>& near) {
  const std::size_t nc = ctx.mesh.num_cells();
  near.assign(nc, 0);
  for (std::size_t c = 0; c < nc; ++c) near[c] = !ctx.cell_valid[c];
  grow_layers(ctx, near, kUntangleReach);
}

// focus[p]: p is an end of an edge (a, b) of a non-positive decomposition tet
// (a, b, F, R) of an invalid cell. The first untangling sweep visits these
// points only, not every point of an invalid cell: on the raw duals of the
// four domains at 100k tets it visits ~660 points instead of ~6,400, leaves
// as few or fewer cells invalid, and the untangled mesh's max kappa/3 is ~70
// instead of ~1,500 (the neighbours of the tangled cells are spared; the
// default's smoothing ends at the same quality). The later untangling
// sweeps, over the cells it left, visit every point of an invalid cell.
void mark_bad_tet_points(const Context& ctx, std::vector<char>& focus) {
  focus.assign(ctx.mesh.num_points(), 0);
  std::vector<std::uint32_t> invalid;
  for (std::uint32_t c = 0; c < ctx.setup.stencil.num_cells(); ++c)
    if (!ctx.cell_valid[c]) invalid.push_back(c);
  // Each invalid cell's bad tets in parallel (exact, as cell_valid), marked
  // serially (the marks are the same in any order).
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> bad(invalid.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, invalid.size(), 16), [&](const auto& r) {
    std::vector<Point3> scratch;
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      star_shaped_bad_tets(ctx.setup.stencil, invalid[i], ctx.mesh.points, scratch, bad[i]);
  });
  for (const auto& tets : bad)
    for (const auto& [j, i] : tets) {
      const auto loop = ctx.setup.stencil.loop(j);
      focus[loop[i].idx] = 1;
      focus[loop[i + 1 == loop.size() ? 0 : i + 1].idx] = 1;
    }
}

// The points an untangling sweep may visit: a superset of those its active
// rule accepts at the sweep's start (the focus points in the first sweep, the
// points of invalid cells in the later ones, and the points of the cells
// changed in the previous sweep within reach of an invalid cell). During the
// sweep the rule accepts no others: cells only become valid (a move that
// would make a valid cell invalid is refused) and this sweep's changes do not
// count until the next. The sweep still asks the rule at each visit.
std::vector<char> untangling_candidates(const Context& ctx, bool first, const std::vector<char>& focus,
                                        const std::vector<int>& last_change, int sweep,
                                        const std::vector<char>& near_invalid) {
  std::vector<char> cand = first ? focus : std::vector<char>(ctx.mesh.num_points(), 0);
  for (std::uint32_t c = 0; c < ctx.setup.stencil.num_cells(); ++c) {
    const bool ring = last_change[c] == sweep - 1 && !near_invalid.empty() && near_invalid[c];
    if ((!first && !ctx.cell_valid[c]) || ring)
      for (PointId q : ctx.setup.stencil.points_of(c)) cand[q.idx] = 1;
  }
  return cand;
}

// A seeded run (the re-optimisation after the split) moves only the points of
// cells within kSeedReach layers of the seed cells and of the invalid cells: the rest of the mesh was
// optimised already, and without a bound the settling rule carries the wave
// of a not fully converged mesh across every colour of one sweep (a 431k-tet
// mesh with 4 vertices cut whole: 191,571 of ~200k points visited).
constexpr int kSeedReach = 3;

// The local scheme's sweeps (run_local), step by step: the untangling phase,
// the smoothing sweeps, then the polish and the OpenFOAM repair.
//
// Active set. A point is visited while a cell around it is invalid, or a point
// of one of its cells moved by more than settle_move x its local length in
// this or the previous sweep (last_change[c] >= sweep - 1); points in settled
// regions are skipped. Untangling phase (up to untangle_sweeps sweeps, while
// invalid cells remain): nothing counts as changed at the start, so only the
// points of the invalid cells' bad tets (first sweep), then the points of
// invalid cells and the growing rings around the points that moved are
// visited. Then one sweep visits every point (the smoothing starts
// everywhere) and later sweeps follow the settling rule.
class LocalRun {
 public:
  explicit LocalRun(Context& ctx);
  void run();

 private:
  const Passes& whole_passes();
  void bound_seeded_run();
  void set_sweep_mode(bool untangling, int sweep);
  const IterationRecord& run_sweep(int sweep, bool untangling);
  bool untangling_ends_run(const IterationRecord& rec);
  void finish(int sweep);

  static constexpr int kNever = -2;
  Context& ctx_;
  const OptimParams& prm_;
  tbb::enumerable_thread_specific<VertexNewton> solvers_;
  // The colouring of every point, made when the first sweep that may visit
  // any point needs it (never while only untangling); an untangling sweep
  // colours its candidates only (untangling_candidates).
  std::optional<Passes> whole_;
  std::vector<std::uint32_t> block_;  // colour_points' scratch
  std::vector<int> last_change_;      // per cell, the last sweep that moved one of its points
  SweepMode mode_;                    // of the current sweep (the polish starts from the last one's)
  // Method::Untangle: only untangling sweeps, as many as max_iter allows.
  const bool untangle_only_;
  int untangle_left_;
  // Seeded (optimize()'s seed_cells): no full sweep; the seed cells count as
  // changed in the sweep before the first, and the rule spreads from there.
  const bool seeded_;
  std::vector<char> reach_;  // seeded: the cells whose points may move
  bool full_sweep_ = false;
  double f_prev_;
  std::vector<char> near_invalid_, focus_;
  std::size_t fewest_invalid_;
  int stalled_ = 0;  // untangling sweeps since the invalid count last dropped
  // No smoothing sweep has run yet (a seeded run's cells around the cuts are
  // badly shaped from the start: the full model from its first sweep).
  bool first_smoothing_;
};

LocalRun::LocalRun(Context& ctx)
    : ctx_(ctx), prm_(ctx.setup.params), solvers_([&ctx] { return VertexNewton(ctx); }),
      block_(ctx.mesh.num_points(), kNoBlock), last_change_(ctx.mesh.num_cells(), kNever),
      untangle_only_(ctx.setup.params.method == OptimParams::Method::Untangle),
      untangle_left_(ctx.report->iterations.back().invalid > 0
                         ? (untangle_only_ ? ctx.setup.params.max_iter : ctx.setup.params.untangle_sweeps)
                         : 0),
      seeded_(!ctx.setup.seed_cells.empty()), f_prev_(ctx.report->iterations.back().objective),
      fewest_invalid_(ctx.report->iterations.back().invalid), first_smoothing_(!seeded_) {}

const Passes& LocalRun::whole_passes() {
  if (!whole_) {
    whole_ = colour_passes(ctx_, block_);
    ctx_.lap("colouring");
  }
  return *whole_;
}

// A seeded run moves the points of the cells within kSeedReach layers of the
// seed and invalid cells only; the seed cells count as changed before sweep 1.
void LocalRun::bound_seeded_run() {
  const std::size_t nc = ctx_.mesh.num_cells();
  reach_.assign(nc, 0);
  for (std::size_t c = 0; c < nc; ++c) reach_[c] = ctx_.setup.seed_cells[c] || !ctx_.cell_valid[c];
  grow_layers(ctx_, reach_, kSeedReach);
  for (std::size_t c = 0; c < nc; ++c)
    if (ctx_.setup.seed_cells[c]) last_change_[c] = 0;
}

// The sweep's relaxation and derivative model (mode_, handed to every visit).
void LocalRun::set_sweep_mode(bool untangling, int sweep) {
  // Untangling sweeps: no over-relaxation, and the full model instead of the
  // corrected lagged one (around a tangled cell the centres' motion is what
  // decides the regularised volumes; the sweeps visit few points).
  mode_.omega = untangling ? 1.0 : prm_.relaxation;
  // The first untangling sweep (the points of every invalid cell) on the
  // plain lagged model: with the centres held, a point of a tangled cell is
  // not dragged to where the regularised volumes of the tangled cell drop
  // fastest at any cost to its valid neighbours, as the full model does
  // (proofs/quality.md §7). The later untangling sweeps, over the few cells
  // it left, use the full model at a point that still has an invalid cell
  // when it is visited (it untangles what the lagged one cannot) and the
  // plain lagged model at the others, whose cells an earlier visit of the
  // sweep made valid (a full-model visit costs ~5x a lagged one; measured
  // at 100k: the same invalid counts per sweep, 40-60% of the visits on the
  // full model, the later sweeps ~25% faster).
  // The first smoothing sweep then uses no full model (kFullModelRatio).
  mode_.untangling = !untangling ? SweepMode::Untangling::None
                     : sweep == 1 ? SweepMode::Untangling::Lagged
                                  : SweepMode::Untangling::FullWhereInvalid;
  mode_.full_model_above =
      first_smoothing_ ? std::numeric_limits<double>::infinity() : kFullModelRatio * ctx_.last_stats.mean;
  first_smoothing_ = first_smoothing_ && untangling;
}

// One sweep over the active points and its record.
const IterationRecord& LocalRun::run_sweep(int sweep, bool untangling) {
  // Untangling: rings grow by one cell layer per sweep (changes of the
  // previous sweep only); smoothing: changes of this or the previous sweep.
  const int since = sweep - 1;
  // The first untangling sweep visits the points of the invalid cells' bad
  // tets only (mark_bad_tet_points); the later ones every point of an invalid cell.
  const bool first_untangling = untangling && sweep == 1;
  // Nothing has changed before the first sweep of a run that is not seeded:
  // no ring to bound.
  if (untangling && (!first_untangling || seeded_)) mark_near_invalid(ctx_, near_invalid_);
  if (first_untangling) mark_bad_tet_points(ctx_, focus_);
  auto active = [&](PointId p) {
    bool a = full_sweep_ || (first_untangling && focus_[p.idx]), in_reach = !seeded_;
    for (std::uint32_t c : ctx_.setup.stencil.cells_of(p)) {
      a = a || (!first_untangling && !ctx_.cell_valid[c]) ||
          (last_change_[c] >= since &&
           (!untangling || (last_change_[c] < sweep && !near_invalid_.empty() && near_invalid_[c])));
      in_reach = in_reach || reach_[c];
    }
    return a && in_reach;
  };
  IterationRecord counts;
  if (untangling) {
    const std::vector<char> cand =
        untangling_candidates(ctx_, first_untangling, focus_, last_change_, sweep, near_invalid_);
    const Passes sub = colour_passes(ctx_, block_, &cand);
    ctx_.lap("colouring");
    sweep_points(ctx_, sub, solvers_, mode_, sweep, last_change_, active, counts);
  } else {
    sweep_points(ctx_, whole_passes(), solvers_, mode_, sweep, last_change_, active, counts);
  }
  return record_sweep(ctx_, sweep, counts);
}

// After an untangling sweep: the phase ends when no cell is invalid, nothing
// moved or kUntangleStall sweeps left as many invalid cells; returns whether
// the run ends with it (Method::Untangle). The objective test is meaningless
// while only a few points move.
bool LocalRun::untangling_ends_run(const IterationRecord& rec) {
  --untangle_left_;
  if (rec.invalid < fewest_invalid_) {
    fewest_invalid_ = rec.invalid;
    stalled_ = 0;
  } else {
    ++stalled_;
  }
  if (rec.invalid == 0 || rec.updates == 0 || stalled_ >= kUntangleStall) untangle_left_ = 0;
  if (untangle_only_ && untangle_left_ == 0) return true;
  full_sweep_ = untangle_left_ == 0 && !seeded_;
  f_prev_ = rec.objective;
  return false;
}

// The polish and, the cells failing OpenFOAM's checks (optim/foam_gate.h),
// a repair descent in one more record; neither while cells are invalid (the
// split cuts and re-optimises them: on a sliver mesh's tangled dual the
// repair cost 4x the sweeps). sweep: the first sweep not run.
// Untangling only, the repair runs when asked (foam_repair_untangle) and
// the polish never.
void LocalRun::finish(int sweep) {
  if (untangle_only_ && !prm_.foam_repair_untangle) return;
  if (!untangle_only_ && prm_.polish_sweeps > 0 && prm_.max_iter > 0 && ctx_.report->iterations.back().invalid == 0)
    polish_worst(ctx_, whole_passes(), solvers_, mode_, sweep, last_change_);
  if (prm_.foam_gate && prm_.max_iter > 0 && ctx_.report->iterations.back().invalid == 0) {
    ctx_.lap("iterations");
    const IterationRecord r = repair_foam(ctx_);
    ctx_.lap("foam_repair");
    if (r.updates > 0) record_sweep(ctx_, ctx_.report->iterations.back().iteration + 1, r);
  }
}

// Untangling sweeps while cells are invalid, then smoothing sweeps until the
// objective drops by less than the tolerance (relative) or max_iter.
void LocalRun::run() {
  if (untangle_only_ && untangle_left_ == 0) return finish(1);
  if (seeded_) bound_seeded_run();
  full_sweep_ = untangle_left_ == 0 && !seeded_;
  int s = 1;
  for (; s <= prm_.max_iter; ++s) {
    const bool untangling = untangle_left_ > 0;
    set_sweep_mode(untangling, s);
    const IterationRecord& rec = run_sweep(s, untangling);
    if (untangling) {
      if (untangling_ends_run(rec)) return finish(s + 1);
      continue;
    }
    full_sweep_ = false;
    const double f = rec.objective;
    if (std::fabs(f_prev_ - f) < prm_.effective_tol() * std::fabs(f_prev_)) break;
    f_prev_ = f;
  }
  finish(s);
}

}  // namespace

void run_local(Context& ctx) { LocalRun(ctx).run(); }

}  // namespace polydual::optim_detail
