// Min-max descent on the worst cells, the local scheme's last stage
// (OptimParams::worst_rounds; proofs/quality.md §8). The smoothing and the
// polish minimise a sum over the cells: at its optimum the worst cell is held
// in balance by its neighbours, and a lower sum can keep a higher max (cube
// 1M: 2.0831 against 2.0820 for the slower default of 5741827). This stage lowers the max
// itself.
//
// A round takes the current worst cell w (the highest quality, the lowest
// index among equals) and visits its movable points in index order until w
// is no longer the worst. At a point p it descends m_p(x) = max over p's
// cells c of q_c(x), the cells' qualities (cell_quality, in doubles: not
// exact, a measure), along the negative forward-difference gradient, in p's
// parametric space, of the soft maximum tau log sum exp(q_c / tau)
// (tau = kSoftShare x m_p: the cells within a few tau of the max steer
// together, so a step that would only trade the worst cell for a neighbour
// is not proposed). A step starts at twice the last accepted length (at
// first and at most kStartStep x the local length) and halves up to
// max_halvings times; a position is accepted only if m_p drops and every cell
// of p that was valid stays valid by the exact star test (the same test as
// the sweeps'). So the mesh's max quality never rises (every changed cell
// ends below the old m_p, itself at most the max) and no valid cell becomes
// invalid.
//
// When no point of the worst cell moves (w is a local min-max optimum of
// these moves) w leaves the candidates and the next round takes the next
// worst. The rounds stop when no candidate is left, after worst_rounds rounds, or when the corners
// evaluated reach kWorkBudget times the corners of one pass over every point's
// cells: the stage's time then grows with the mesh and nothing else (a coarse
// mesh's few large cells made its rounds cost 40x its sweeps). Serial, in a fixed
// order: deterministic for any thread count. A round visits one or a few
// points; the worst cell is the first of an ordered set of the cells above a
// threshold, not found by a scan of every cell per round.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <span>
#include <vector>

#include "optim/context.h"
#include "quality/metrics.h"
#include "quality/star_verdict.h"

namespace polydual::optim_detail {
namespace {

constexpr double kSoftShare = 2e-3;  // tau of the soft maximum, relative to m_p
constexpr double kStartStep = 0.2;  // first step length, relative to cbrt(mean V0 of p's cells)
constexpr int kStepsPerVisit = 4;    // accepted steps at most per visit
// The candidate set holds the cells whose quality exceeds the mean plus this
// share of (max - mean) at the start; a cell that rises above that threshold
// later joins it.
constexpr double kCandidateShare = 0.5;
// The work bound, in passes over every point's cells (corners evaluated by the
// quality measure and the star test); about 5x the sweeps' own measurements.
constexpr double kWorkBudget = 16;

// The cells above a threshold, ordered by quality (highest first, then the
// lowest index): the worst cell is the first.
class WorstCells {
 public:
  WorstCells(const std::vector<double>& q, double threshold) : threshold_(threshold) {
    for (std::uint32_t c = 0; c < q.size(); ++c)
      if (q[c] > threshold_) set_.insert({q[c], c});
  }
  bool empty() const { return set_.empty(); }
  // The worst cell; UINT32_MAX if none is above the threshold.
  std::uint32_t worst() const { return set_.empty() ? UINT32_MAX : set_.begin()->second; }
  // Cell c (quality q) leaves the set: no move of its points lowers it.
  // It comes back if a neighbour's move changes its quality (update()).
  void drop(std::uint32_t c, double q) { set_.erase({q, c}); }
  // Cell c's quality changed from `before` to `after`.
  void update(std::uint32_t c, double before, double after) {
    if (before > threshold_) set_.erase({before, c});
    if (after > threshold_) set_.insert({after, c});
  }

 private:
  struct Order {
    bool operator()(const std::pair<double, std::uint32_t>& a, const std::pair<double, std::uint32_t>& b) const {
      return a.first != b.first ? a.first > b.first : a.second < b.second;
    }
  };
  double threshold_;
  std::set<std::pair<double, std::uint32_t>, Order> set_;
};

class WorstDescent {
 public:
  explicit WorstDescent(Context& ctx) : ctx_(ctx) {}

  // Corners evaluated so far, and the cost of evaluating every point's cells once.
  std::uint64_t work() const { return work_; }
  std::uint64_t pass_cost() const {
    std::uint64_t corners = 0;
    for (std::uint32_t c = 0; c < ctx_.setup.stencil.num_cells(); ++c)
      corners += ctx_.setup.stencil.num_corners(c, ctx_.setup.params.metric) * ctx_.setup.stencil.points_of(c).size();
    return corners;
  }

  // Up to kStepsPerVisit accepted steps at p while w is the worst cell;
  // returns how many. The qualities of p's cells are kept current in
  // ctx.cell_quality and in `worst`.
  int visit(PointId p, std::uint32_t w, WorstCells& worst) {
    const int k = ctx_.setup.dof[p.idx];
    if (k == 0) return 0;
    if (ctx_.bc) ctx_.bc->ensure(p);
    const auto cells = ctx_.setup.stencil.cells_of(p);
    double v0 = 0;
    for (std::uint32_t c : cells) v0 += ctx_.setup.V0[c];
    const double ell = std::cbrt(v0 / static_cast<double>(cells.size()));
    int accepted = 0;
    double alpha = kStartStep * ell;  // each step starts at twice the last accepted length
    before_.clear();
    for (std::uint32_t c : cells) before_.push_back(ctx_.cell_quality[c]);
    while (accepted < kStepsPerVisit && step(p, k, ell, cells, alpha)) {
      ++accepted;
      ctx_.touched[p.idx] = 1;
      for (std::size_t i = 0; i < cells.size(); ++i) {  // q_: the accepted position's (gates_commit stored them)
        worst.update(cells[i], before_[i], q_[i]);
        before_[i] = q_[i];
      }
      if (worst.worst() != w) break;  // w is no longer the worst
    }
    return accepted;
  }

 private:
  // The qualities of p's cells with p at x (into q_), and their max.
  double measure(PointId p, const Point3& x, std::span<const std::uint32_t> cells) {
    Point3& slot = ctx_.mesh.points[p.idx];
    const Point3 keep = slot;
    slot = x;
    q_.clear();
    double m = -std::numeric_limits<double>::infinity();
    for (std::uint32_t c : cells) {
      work_ += ctx_.setup.stencil.num_corners(c, ctx_.setup.params.metric);
      q_.push_back(polydual::cell_quality(ctx_.setup.stencil, c, ctx_.setup.params.metric, ctx_.mesh.points));
      m = std::max(m, q_.back());
    }
    slot = keep;
    return m;
  }
  // The soft maximum m + tau log sum exp((q - m) / tau) of q (m its max).
  static double soft_max(std::span<const double> q, double m, double tau) {
    double sum = 0;
    for (double v : q) sum += std::exp((v - m) / tau);
    return m + tau * std::log(sum);
  }

  // One descent step at p from length `alpha` (then halved); true if a
  // position was accepted (q_ then holds its qualities), and alpha is then
  // twice its length (at most kStartStep x ell).
  bool step(PointId p, int k, double ell, std::span<const std::uint32_t> cells, double& alpha) {
    const Point3 o = ctx_.mesh.points[p.idx];
    Vec3 B[3];
    ctx_.basis(p, B);
    // The current qualities are ctx.cell_quality's (kept current).
    q0_.clear();
    double m0 = -std::numeric_limits<double>::infinity();
    for (std::uint32_t c : cells) {
      q0_.push_back(ctx_.cell_quality[c]);
      m0 = std::max(m0, q0_.back());
    }
    if (!std::isfinite(m0)) return false;
    const double tau = kSoftShare * m0;
    const double f0 = soft_max(q0_, m0, tau);
    // Forward differences of the soft maximum along each basis vector (a
    // direction, not a decision: k evaluations instead of 2k).
    const double h = ctx_.setup.params.fd_step * ell;
    double g[3] = {0, 0, 0}, gn = 0;
    for (int i = 0; i < k; ++i) {
      const double m = measure(p, o + h * B[i], cells);
      g[i] = std::isfinite(m) ? (soft_max(q_, m, tau) - f0) / h : 0.0;
      gn += g[i] * g[i];
    }
    gn = std::sqrt(gn);
    if (!(gn > 0) || !std::isfinite(gn)) return false;
    for (int hv = 0; hv <= ctx_.setup.params.max_halvings; ++hv, alpha *= 0.5) {
      Point3 x = o;
      for (int i = 0; i < k; ++i) x += (-alpha * g[i] / gn) * B[i];
      std::uint32_t prim = BoundaryConstraints::kNone;
      if (k < 3) x = ctx_.bc->project(p, x, &prim);
      if (!(measure(p, x, cells) < m0)) continue;
      ctx_.mesh.points[p.idx] = x;
      // Exact: the star test; then the floating-point gates (context.h).
      if (keeps_valid(cells) && ctx_.gates_accept(cells, qg_)) {
        if (k < 3) ctx_.bc->commit(p, prim);
        ctx_.gates_commit(cells, qg_);
        alpha = std::min(2 * alpha, kStartStep * ell);
        return true;
      }
      ctx_.mesh.points[p.idx] = o;
    }
    return false;
  }

  // Exact: every cell of p that is valid stays valid (the star test).
  bool keeps_valid(std::span<const std::uint32_t> cells) {
    for (std::uint32_t c : cells) {
      work_ += ctx_.setup.stencil.num_corners(c, ctx_.setup.params.metric);
      if (ctx_.cell_valid[c] && !star_shaped_verdict(ctx_.setup.stencil, c, ctx_.mesh.points, true, scratch_).valid)
        return false;
    }
    return true;
  }

  Context& ctx_;
  std::uint64_t work_ = 0;
  std::vector<double> q_, q0_, qg_, before_;
  std::vector<Point3> scratch_;
};

}  // namespace

IterationRecord descend_worst(Context& ctx) {
  IterationRecord counts;
  // ctx.cell_quality is current (the polish refreshes the cells it moves).
  double sum = 0, max = -std::numeric_limits<double>::infinity();
  std::size_t n = 0;
  for (double q : ctx.cell_quality)
    if (std::isfinite(q)) { sum += q; max = std::max(max, q); ++n; }
  const double mean = n > 0 ? sum / static_cast<double>(n) : 0.0;
  if (ctx.setup.params.worst_rounds <= 0 || !(max > mean)) return counts;
  // A mesh whose worst cells are far above the bound takes every cell above
  // the bound as a candidate: a cell that cannot improve (its points pinned
  // at model vertices, say) is dropped, and the next worst gets the rounds.
  const double threshold = std::min(mean + kCandidateShare * (max - mean), std::max(OptimReport::kWorstBound, mean));
  WorstCells worst(ctx.cell_quality, threshold);
  WorstDescent descent(ctx);
  const double budget = kWorkBudget * static_cast<double>(descent.pass_cost());
  for (int round = 0; round < ctx.setup.params.worst_rounds && !worst.empty() && double(descent.work()) < budget; ++round) {
    const std::uint32_t w = worst.worst();
    std::uint64_t moved = 0;
    for (PointId p : ctx.setup.stencil.points_of(w)) {
      ++counts.visited;
      moved += static_cast<std::uint64_t>(descent.visit(p, w, worst));
      if (worst.worst() != w) break;  // w is no longer the worst: the next round takes the new one
    }
    counts.updates += moved;
    if (moved == 0) worst.drop(w, ctx.cell_quality[w]);  // w is a local min-max optimum: the next worst
  }
  return counts;
}

}  // namespace polydual::optim_detail
