#include "split/coarsen.h"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <utility>

#include "core/stopwatch.h"
#include "core/union_find.h"
#include "dual/build_dual.h"
#include "quality/metrics.h"
#include "mesh/sub_mesh.h"
#include "quality/star_verdict.h"
#include "quality/stencil.h"
#include "split/cuts.h"
#include "split/local_round.h"
#include "split/recheck.h"

namespace polydual {

Json CoarsenStats::to_json() const {
  Json j = Json::object();
  j.set("passes", passes);
  j.set("evaluations", evaluations);
  j.set("merges_proposed", merges_proposed);
  j.set("merges_kept", merges_kept);
  j.set("reverts", reverts);
  j.set("bisections", bisections);
  return j;
}

namespace {

// Calls f(k, o, triangle) for each interior triangle through v on no model
// face, once per pair of star tets k < o (star ranks) that share it.
template <class F>
void for_star_joins(const ClassifiedTetMesh& m, VertexId v, F&& f) {
  const std::span<const TetId> tets = m.vertex_tets(v);
  for (std::size_t k = 0; k < tets.size(); ++k) {
    const int apex = m.local_index(tets[k], v);
    for (int i = 0; i < 4; ++i) {
      if (i == apex) continue;
      const TetId o = m.tet_neighbor(tets[k], i);
      if (!o.valid()) continue;
      const TriId t = m.tet_triangle(tets[k], i);
      if (m.on_model_face(t)) continue;
      const std::uint32_t r = m.star_rank(v, o);
      if (k < r) f(std::uint32_t(k), r, t);
    }
  }
}

// A whole vertex being coarsened: its classes as a union-find over its star
// tets, and the pairs of star tets it may join (sharing an interior
// triangle through v that no free-edge cut of v separates).
struct Vertex {
  VertexId v;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> joins;
  std::uint32_t size = 0;  // star tets
  UnionFind parent{0}, saved{0};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> picks;      // this pass's merges (class roots)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> forbidden;  // merges taken back (star tets)
  int failures = 0;
  bool done = false, proposing = false, partial = false;

  std::vector<std::uint32_t> labels() {
    std::vector<std::uint32_t> l(size);
    for (std::uint32_t k = 0; k < l.size(); ++k) l[k] = parent.find(k);
    return l;
  }
};

Vertex make_vertex(const ClassifiedTetMesh& m, const VertexCuts& free_edge, VertexId v) {
  Vertex x;
  x.v = v;
  x.size = std::uint32_t(m.vertex_tets(v).size());
  x.parent = UnionFind(x.size);
  for_star_joins(m, v, [&](std::uint32_t k, std::uint32_t o, TriId t) {
    if (!free_edge.cuts(v, t)) x.joins.emplace_back(k, o);
  });
  return x;
}

// Whether merging the classes with roots ra and rb was taken back before.
bool forbidden_pair(Vertex& x, std::uint32_t ra, std::uint32_t rb) {
  for (const auto& [a, b] : x.forbidden) {
    const std::uint32_t fa = x.parent.find(a), fb = x.parent.find(b);
    if ((fa == ra && fb == rb) || (fa == rb && fb == ra)) return true;
  }
  return false;
}

// Proposes a matching of x's adjacent classes (the first pair of each class
// in join order), at most (matching size >> failures) of them, at least one;
// merges them. Returns the number of merges.
std::size_t propose(Vertex& x) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> cand;
  for (const auto& [a, b] : x.joins) {
    const std::uint32_t ra = x.parent.find(a), rb = x.parent.find(b);
    if (ra != rb && !forbidden_pair(x, ra, rb)) cand.emplace_back(std::min(ra, rb), std::max(ra, rb));
  }
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  std::vector<char> matched(x.size, 0);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pick;
  for (const auto& [a, b] : cand)
    if (!matched[a] && !matched[b]) {
      matched[a] = matched[b] = 1;
      pick.emplace_back(a, b);
    }
  if (pick.empty()) return 0;
  pick.resize(std::max<std::size_t>(1, pick.size() >> x.failures));
  x.saved = x.parent;
  x.picks = std::move(pick);
  for (const auto& [a, b] : x.picks) x.parent.unite(a, b);  // roots, a < b: b joins a
  return x.picks.size();
}

// free_edge with the label cuts of each whole vertex xs[i] (labels[i]: a
// label per star tet), the vertices marked whole.
VertexCuts cuts_of_labels(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                          std::span<const Vertex> xs, std::span<const std::vector<std::uint32_t>> labels) {
  std::vector<std::pair<VertexId, TriId>> pairs;
  for (std::size_t v = 0; v + 1 < free_edge.off.size(); ++v)
    for (TriId f : free_edge.of(VertexId(v))) pairs.emplace_back(VertexId(v), f);
  for (std::size_t i = 0; i < xs.size(); ++i) label_cuts(m, xs[i].v, labels[i], pairs);
  VertexCuts c = VertexCuts::from_pairs(m.num_vertices(), std::move(pairs));
  c.whole.assign(whole.begin(), whole.end());
  return c;
}

VertexCuts cuts_of(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                   std::vector<Vertex>& xs) {
  std::vector<std::vector<std::uint32_t>> labels;
  labels.reserve(xs.size());
  for (Vertex& x : xs) labels.push_back(x.labels());
  return cuts_of_labels(m, free_edge, whole, xs, labels);
}

// Whether a vertex of x.v's star other than x.v is marked in bad.
bool neighbour_bad(const ClassifiedTetMesh& m, const Vertex& x, const std::vector<char>& bad) {
  for (TetId t : m.vertex_tets(x.v))
    for (VertexId w : m.tet(t))
      if (w != x.v && bad[w.idx]) return true;
  return false;
}

void revert_all(Vertex& x, CoarsenStats& st) {
  x.parent = x.saved;
  x.picks.clear();
  x.proposing = false;
  x.done = ++x.failures >= kMaxFailures;
  ++st.reverts;
}

// Takes back the merges of this pass that made the classes holding the bad
// sides of x.v (sides of the trial's cuts) and forbids them.
void revert_sides(const ClassifiedTetMesh& m, Vertex& x, const VertexCuts& cuts, std::span<const std::uint32_t> sides) {
  const std::vector<std::uint32_t> side = star_sides(m, x.v, &cuts);
  std::vector<char> bad_root(x.size, 0);
  for (std::uint32_t k = 0; k < side.size(); ++k)
    if (std::find(sides.begin(), sides.end(), side[k]) != sides.end()) bad_root[x.parent.find(k)] = 1;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keep;
  for (const auto& pr : x.picks) {
    if (bad_root[x.parent.find(pr.first)]) x.forbidden.push_back(pr);
    else keep.push_back(pr);
  }
  x.parent = x.saved;
  x.picks = std::move(keep);
  for (const auto& [a, b] : x.picks) x.parent.unite(a, b);
  x.proposing = !x.picks.empty();
  x.partial = true;
}

// Evaluates the proposals and takes merges back (coarsen.h) until no cell is
// invalid.
void settle(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
            std::vector<Vertex>& xs, const CutsEvaluator& evaluate, CoarsenStats& st) {
  for (Vertex& x : xs) x.partial = false;
  for (;;) {
    const VertexCuts cuts = cuts_of(m, free_edge, whole, xs);
    const std::vector<BadCell> cells = evaluate(cuts);
    ++st.evaluations;
    if (cells.empty()) return;
    std::vector<char> bad(m.num_vertices(), 0);
    for (const BadCell& c : cells) bad[c.v.idx] = 1;
    bool acted = false;
    for (Vertex& x : xs) {
      if (!x.proposing) continue;
      if (bad[x.v.idx] && !x.partial) {
        std::vector<std::uint32_t> sides;
        for (const BadCell& c : cells)
          if (c.v == x.v) sides.push_back(c.side);
        revert_sides(m, x, cuts, sides);
      } else if (bad[x.v.idx] || neighbour_bad(m, x, bad)) {
        revert_all(x, st);
      } else {
        continue;
      }
      acted = true;
    }
    if (!acted) {
      bool any = false;
      for (Vertex& x : xs)
        if (x.proposing) revert_all(x, st), any = true;
      if (!any) return;  // not reached: the cuts the pass started from were valid
    }
  }
}

// The direction of largest spread of the unit vectors from v to the
// centroids of the star tets `ranks` (into dirs, in that order): the leading
// eigenvector of their covariance, by power iteration from a fixed start
// (deterministic). Floating point: it only proposes a split, the exact star
// test judges it. (Measured on TetGen and Gmsh meshes without the
// optimiser: the covariance about the mean direction, and a plane through
// v, keep 10-30 % fewer cells than the second moment and a median split;
// the other two axes and the mean direction, 5-70 % more.)
Vec3 spread_direction(const ClassifiedTetMesh& m, VertexId v, std::span<const std::uint32_t> ranks,
                      std::vector<Vec3>& dirs) {
  const std::span<const TetId> tets = m.vertex_tets(v);
  dirs.clear();
  Vec3 mean{};
  for (std::uint32_t k : ranks) {
    Vec3 c{};
    for (VertexId w : m.tet(tets[k])) c += m.point(w);
    Vec3 d = 0.25 * c - m.point(v);
    const double len = norm(d);
    d = len > 0 ? d / len : Vec3{};
    dirs.push_back(d);
    mean += d;
  }
  mean = mean / double(std::max<std::size_t>(1, dirs.size()));
  double a[3][3] = {};
  for (const Vec3& d0 : dirs) {
    const Vec3 d = d0 - mean;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) a[i][j] += d[i] * d[j];
  }
  Vec3 n{1.0, 0.5, 0.25};
  for (int iter = 0; iter < 64; ++iter) {
    Vec3 next{};
    for (int i = 0; i < 3; ++i) next[i] = a[i][0] * n.x + a[i][1] * n.y + a[i][2] * n.z;
    const double len = norm(next);
    if (!(len > 0)) break;
    n = next / len;
  }
  return n;
}

// Bisects the class `cls` of v's star tets (label: one per star tet) by the
// plane through v across spread_direction: the tets on its far side get the
// label `fresh` (design §8, "planes through the vertex").
void bisect_class(const ClassifiedTetMesh& m, VertexId v, std::vector<std::uint32_t>& label, std::uint32_t cls,
                  std::uint32_t fresh) {
  std::vector<std::uint32_t> ranks;
  for (std::uint32_t k = 0; k < label.size(); ++k)
    if (label[k] == cls) ranks.push_back(k);
  std::vector<Vec3> dirs;
  const Vec3 n = spread_direction(m, v, ranks, dirs);
  std::vector<std::pair<double, std::uint32_t>> key;
  for (std::size_t i = 0; i < ranks.size(); ++i) key.emplace_back(dot(dirs[i], n), ranks[i]);
  std::sort(key.begin(), key.end());
  // The plane through v; the median when all the tets are on one side.
  std::size_t cut = 0;
  while (cut < key.size() && key[cut].first <= 0) ++cut;
  if (cut == 0 || cut == key.size()) cut = key.size() / 2;
  for (std::size_t i = cut; i < key.size(); ++i) label[key[i].second] = fresh;
}

// The coarsening's first step with CoarsenStart::TopDown (coarsen.h): each
// whole vertex xs[i] labels its star tets (label[i]), all alike at first;
// while a trial has failing cells, the class of each is bisected. Only the
// cells of a vertex whose labels changed can change (proofs/split.md L6,
// Claim 1), and a class of one tet is its corner, as at the start: a
// failing cell is always a class of several tets. The labels reached
// become xs's classes.
void top_down(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
              std::vector<Vertex>& xs, const CutsEvaluator& evaluate, CoarsenStats& st) {
  std::vector<std::int32_t> index_of(m.num_vertices(), -1);
  std::vector<std::vector<std::uint32_t>> label;
  std::vector<std::uint32_t> fresh(xs.size(), 1);  // per whole vertex, the next unused label
  for (std::size_t i = 0; i < xs.size(); ++i) {
    index_of[xs[i].v.idx] = std::int32_t(i);
    label.emplace_back(xs[i].size, 0u);
  }
  for (;;) {
    const VertexCuts cuts = cuts_of_labels(m, free_edge, whole, xs, label);
    const std::vector<BadCell> bad = evaluate(cuts);
    ++st.evaluations;
    if (bad.empty()) break;
    std::vector<std::pair<std::size_t, std::uint32_t>> split;  // (xs index, class)
    for (const BadCell& c : bad) {
      const std::int32_t i = index_of[c.v.idx];
      const std::vector<std::uint32_t> side = i < 0 ? std::vector<std::uint32_t>{} : star_sides(m, c.v, &cuts);
      const std::size_t k = std::size_t(std::find(side.begin(), side.end(), c.side) - side.begin());
      if (k == side.size() || std::count(side.begin(), side.end(), c.side) < 2)
        throw std::logic_error("coarsen top-down: a cell that is not a merged class failed");
      split.emplace_back(std::size_t(i), label[std::size_t(i)][k]);
    }
    std::sort(split.begin(), split.end());
    split.erase(std::unique(split.begin(), split.end()), split.end());
    for (const auto& [i, cls] : split) bisect_class(m, xs[i].v, label[i], cls, fresh[i]++);
    st.bisections += split.size();
  }
  for (std::size_t i = 0; i < xs.size(); ++i) {
    std::vector<std::uint32_t> first(fresh[i], ~0u);  // per label, its first tet
    for (std::uint32_t k = 0; k < xs[i].size; ++k) {
      std::uint32_t& f = first[label[i][k]];
      if (f == ~0u) f = k;
      xs[i].parent.unite(f, k);
    }
  }
}

}  // namespace

void label_cuts(const ClassifiedTetMesh& m, VertexId v, std::span<const std::uint32_t> label,
                std::vector<std::pair<VertexId, TriId>>& out) {
  for_star_joins(m, v, [&](std::uint32_t k, std::uint32_t o, TriId t) {
    if (label[k] != label[o]) out.emplace_back(v, t);
  });
}

VertexCuts coarsen_whole_cuts(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                              const CutsEvaluator& evaluate, CoarsenStats* stats, int max_passes, CoarsenStart start) {
  CoarsenStats st;
  std::vector<Vertex> xs;
  for (std::size_t v = 0; v < whole.size(); ++v)
    if (whole[v]) xs.push_back(make_vertex(m, free_edge, VertexId(v)));
  if (start == CoarsenStart::TopDown && !xs.empty()) top_down(m, free_edge, whole, xs, evaluate, st);
  for (int pass = 0; pass < max_passes; ++pass) {
    std::size_t proposers = 0;
    for (Vertex& x : xs) {
      x.proposing = false;
      if (x.done) continue;
      const std::size_t n = propose(x);
      x.proposing = n > 0;
      x.done = !x.proposing;
      proposers += x.proposing;
      st.merges_proposed += n;
    }
    if (proposers == 0) break;
    ++st.passes;
    settle(m, free_edge, whole, xs, evaluate, st);
    for (const Vertex& x : xs)
      if (x.proposing) st.merges_kept += x.picks.size();
  }
  if (stats) *stats = st;
  return cuts_of(m, free_edge, whole, xs);
}

namespace {
// Point indices sorted by (origin, index), and the origin key of each.
std::vector<std::pair<std::uint64_t, std::uint32_t>> by_origin(const PolyMesh& pm) {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> k(pm.points.size());
  for (std::size_t i = 0; i < k.size(); ++i) {
    const PointOrigin o = pm.point_origin[i];
    k[i] = {(std::uint64_t(std::uint8_t(o.dim + 1)) << 32) | o.id, std::uint32_t(i)};
  }
  std::sort(k.begin(), k.end());
  return k;
}
}  // namespace

std::vector<PointId> warm_start_by_rank(PolyMesh& fresh, const PolyMesh& old) {
  std::vector<PointId> from_old(fresh.points.size(), PointId::invalid());
  if (fresh.point_origin.size() != fresh.points.size() || old.point_origin.size() != old.points.size())
    return from_old;
  const auto a = by_origin(fresh), b = by_origin(old);
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const std::uint64_t key = std::min(a[i].first, b[j].first);
    std::size_t i1 = i, j1 = j;
    while (i1 < a.size() && a[i1].first == key) ++i1;
    while (j1 < b.size() && b[j1].first == key) ++j1;
    if (i1 - i == j1 - j && key >> 32 != 0)  // dim -1: no origin
      for (std::size_t k = 0; k < i1 - i; ++k) {
        fresh.points[a[i + k].second] = old.points[b[j + k].second];
        from_old[a[i + k].second] = PointId(b[j + k].second);
      }
    i = i1;
    j = j1;
  }
  return from_old;
}

// The cells `check` found invalid, as (vertex, side): the primal vertex
// (internal numbering) and the cell's rank among that vertex's cells.
namespace {

// Trials judged locally, when no optimiser moved a point (every point is
// where the build puts it). A whole vertex's cells depend on its own cuts
// only (proofs/split.md L6, Claim 1), so each trial builds, on the sub-mesh
// of their stars, only the cells of the whole vertices whose cuts differ
// from the last trial's (a sub-mesh's cells of a vertex whose star it holds
// are its cells in the whole mesh's dual: L5) and star-tests them exactly;
// the others keep their failing sides. A merged cell above
// max(kMergeQualityBound, its vertex's worst corner) fails too.
class LocalTrials {
 public:
  // start: the cuts the coarsening starts from (every cell valid).
  LocalTrials(const ClassifiedTetMesh& m, const DualParams& dual, Metric metric, const std::vector<double>& worst,
              const VertexCuts& start)
      : m_(m), dual_(dual), metric_(metric), worst_(worst), collapse_(dual_collapse_length(m, dual)),
        cuts_(m.num_vertices()), bad_(m.num_vertices()) {
    for (std::size_t v = 0; v < start.whole.size(); ++v)
      if (start.whole[v]) cuts_[v].assign(start.of(VertexId(v)).begin(), start.of(VertexId(v)).end());
  }

  std::vector<BadCell> operator()(const VertexCuts& cuts) {
    std::vector<VertexId> changed;
    for (std::size_t v = 0; v < cuts.whole.size(); ++v) {
      const std::span<const TriId> now = cuts.of(VertexId(v));
      if (cuts.whole[v] && !std::equal(now.begin(), now.end(), cuts_[v].begin(), cuts_[v].end())) {
        changed.push_back(VertexId(v));
        cuts_[v].assign(now.begin(), now.end());
        bad_[v].clear();
      }
    }
    if (!changed.empty()) test(cuts, changed);
    std::vector<BadCell> bad;
    for (std::size_t v = 0; v < bad_.size(); ++v)
      for (std::uint32_t side : bad_[v]) bad.push_back({VertexId(v), side});
    return bad;
  }

 private:
  // The failing sides of the changed vertices' cells into bad_.
  void test(const VertexCuts& cuts, const std::vector<VertexId>& changed) {
    const std::vector<TetId> tets = star_tets(m_, changed);
    const bool on_whole = double(tets.size()) > kWholeMeshShare * double(m_.num_tets());
    const SubMesh sub = on_whole ? SubMesh{} : sub_mesh(m_, tets);
    const ClassifiedTetMesh& mesh = on_whole ? m_ : sub.mesh;
    std::vector<char> active(mesh.num_vertices(), 0);
    if (on_whole)
      for (VertexId v : changed) active[v.idx] = 1;
    else
      for (std::size_t v = 0; v < sub.vertex.size(); ++v)
        active[v] = std::binary_search(changed.begin(), changed.end(), sub.vertex[v]);
    const VertexCuts local_cuts = on_whole ? cuts : restrict_cuts(m_, sub, cuts);
    const DualScope scope{active, collapse_};
    const PolyMesh pm = build_dual(mesh, dual_, nullptr, &local_cuts, &scope);
    // Cells come by vertex (input numbering, increasing), then by side.
    std::vector<std::uint32_t> cells, vertex_of;
    for (std::size_t c = 0, v = 0; c < pm.num_cells(); ++c) {
      while (v < mesh.num_vertices() && mesh.input_vertex(VertexId(v)) != pm.cell_primal[c].idx) ++v;
      if (v == mesh.num_vertices()) throw std::logic_error("coarsen's local trial: cells not in vertex order");
      if (!active[v]) continue;
      cells.push_back(std::uint32_t(c));
      vertex_of.push_back(on_whole ? std::uint32_t(v) : sub.vertex[v].idx);
    }
    std::vector<CellVerdict> verdicts(pm.num_cells());
    star_shaped_verdicts_of(pm, cells, verdicts, {});
    const MeshStencil stencil = build_stencil(pm);
    std::uint32_t rank = 0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      rank = i > 0 && vertex_of[i] == vertex_of[i - 1] ? rank + 1 : 0;
      const std::uint32_t v = vertex_of[i];
      if (!verdicts[cells[i]].valid ||
          cell_quality(stencil, cells[i], metric_, pm.points) > std::max(kMergeQualityBound, worst_[v]))
        bad_[v].push_back(rank);
    }
  }

  const ClassifiedTetMesh& m_;
  const DualParams& dual_;
  Metric metric_;
  const std::vector<double>& worst_;
  double collapse_;
  std::vector<std::vector<TriId>> cuts_;        // per whole vertex, its cuts in the last trial
  std::vector<std::vector<std::uint32_t>> bad_;  // and its failing sides there
};

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

}  // namespace

std::uint32_t cell_side(const PolyMesh& mesh, std::uint32_t c) {
  std::uint32_t first = c;
  while (first > 0 && mesh.cell_primal[first - 1] == mesh.cell_primal[c]) --first;
  return c - first;
}

VertexCuts split_back(const ClassifiedTetMesh& m, const VertexCuts& cuts, std::span<const BadCell> cells) {
  std::vector<std::pair<VertexId, TriId>> pairs;
  for (std::size_t v = 0; v + 1 < cuts.off.size(); ++v)
    for (TriId f : cuts.of(VertexId(v))) pairs.emplace_back(VertexId(v), f);
  std::vector<BadCell> listed(cells.begin(), cells.end());
  std::sort(listed.begin(), listed.end(), [](const BadCell& a, const BadCell& b) {
    return a.v.idx != b.v.idx ? a.v.idx < b.v.idx : a.side < b.side;
  });
  for (std::size_t i = 0; i < listed.size();) {
    const VertexId v = listed[i].v;
    // The sides of v: its star tets joined through interior triangles that
    // no cut of v separates, numbered by their first tet in star order.
    const std::uint32_t n = std::uint32_t(m.vertex_tets(v).size());
    UnionFind uf(n);
    for_star_joins(m, v, [&](std::uint32_t k, std::uint32_t o, TriId t) {
      if (!cuts.cuts(v, t)) uf.unite(k, o);
    });
    std::vector<std::uint32_t> side_of_root(n, ~0u), side(n);
    std::uint32_t sides = 0;
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t r = uf.find(k);
      if (side_of_root[r] == ~0u) side_of_root[r] = sides++;
      side[k] = side_of_root[r];
    }
    std::vector<char> target(sides, 0);
    for (; i < listed.size() && listed[i].v == v; ++i)
      if (listed[i].side < sides) target[listed[i].side] = 1;
    for_star_joins(m, v, [&](std::uint32_t k, std::uint32_t o, TriId t) {
      if (target[side[k]] || target[side[o]]) pairs.emplace_back(v, t);
    });
  }
  VertexCuts out = VertexCuts::from_pairs(m.num_vertices(), std::move(pairs));
  out.whole = cuts.whole;
  return out;
}

// Merges the barycentric corners of the whole vertices back while every cell
// stays valid (split/coarsen.h). A trial is the dual rebuilt with the trial's
// cuts, every point at its position in the last valid mesh (the base: the split's
// kept mesh at first; merging keeps every point, dual/cut_topology.h kCentre), star-tested
// exactly (cells equal to one of the base keep their verdict). A merged cell
// whose quality is above both kMergeQualityBound and the worst of its
// vertex's corners counts as a failure too (floating point: it only steers
// the merging), so merging does not make a vertex's worst cell worse. A
// trial with no failure becomes the base; the last base is left in
// mesh and check_base,
// and the split's final optimisation then smooths it. (Untangling each trial
// before judging it kept 7-30 % more merges but cost up to 19 s on a
// 13k-tet TetGen mesh against 0.5 s: measured.)
namespace {
// The whole build of cuts judged by local trials, checked exactly, in mesh
// and check when no cell is invalid; false (both untouched) otherwise.
bool adopt_whole_build(const ClassifiedTetMesh& m, const DualParams& dual, const VertexCuts& cuts, PolyMesh& mesh,
                       CheckResult& check) {
  PolyMesh fresh = build_dual(m, dual, nullptr, &cuts);
  const std::vector<PointId> from_old = warm_start_by_rank(fresh, mesh);
  CheckResult c = recheck_mesh(fresh, mesh, check, from_old);
  if (c.invalid_cells > 0) return false;
  mesh = std::move(fresh);
  check = std::move(c);
  return true;
}
}  // namespace

Json coarsen_split(const ClassifiedTetMesh& m, const DualParams& dual, Metric metric, SplitState& st, PolyMesh& mesh,
                   CheckResult& check_base, CoarsenStart start, bool local) {
  const Stopwatch clock;
  VertexCuts base_cuts = st.cuts;
  const std::vector<double> worst =
      whole_cell_quality(st, st.cuts, mesh, check_base, metric, nullptr, kMergeQualityBound, nullptr);
  // Without an optimiser every point is where the build puts it: trials are
  // judged locally (LocalTrials) and the cuts kept are built once at the end.
  bool local_trials = local && start == CoarsenStart::TopDown;
  std::optional<LocalTrials> trials;  // only then: it copies every whole vertex's cuts
  if (local_trials) trials.emplace(m, dual, metric, worst, st.cuts);
  auto evaluate = [&](const VertexCuts& cuts) {
    if (local_trials) {
      std::vector<BadCell> bad = (*trials)(cuts);
      if (bad.empty()) base_cuts = cuts;
      return bad;
    }
    PolyMesh fresh = build_dual(m, dual, nullptr, &cuts);
    const std::vector<PointId> from_old = warm_start_by_rank(fresh, mesh);
    CheckResult check = recheck_mesh(fresh, mesh, check_base, from_old);
    std::vector<BadCell> bad = bad_cells(st, fresh, check);
    whole_cell_quality(st, cuts, fresh, check, metric, &worst, kMergeQualityBound, &bad);
    if (bad.empty()) {
      mesh = std::move(fresh);
      check_base = std::move(check);
      base_cuts = cuts;
    }
    return bad;
  };
  const std::size_t cells_before = mesh.num_cells();
  CoarsenStats cs;
  VertexCuts coarse = coarsen_whole_cuts(m, st.free_edge, st.cuts.whole, evaluate, &cs, kCoarsenMaxPasses, start);
  if (local_trials && !adopt_whole_build(m, dual, base_cuts, mesh, check_base)) {
    // Not expected (L5, L6): the coarsening again, every trial a whole build.
    local_trials = false;
    base_cuts = st.cuts;
    cs = CoarsenStats{};
    coarse = coarsen_whole_cuts(m, st.free_edge, st.cuts.whole, evaluate, &cs, kCoarsenMaxPasses, start);
  }
  Json j = cs.to_json();
  j.set("trials", local_trials ? "local" : "whole");
  j.set("cells_before", cells_before);
  j.set("cells_after", mesh.num_cells());
  // The coarsening ends on the cuts of its last valid trial (or where it began).
  if (!(coarse.tri == base_cuts.tri) || !(coarse.whole == base_cuts.whole))
    throw std::logic_error("coarsen_split: the coarsened cuts are not those of the last valid trial");
  st.cuts = std::move(base_cuts);
  j.set("seconds", clock.seconds());
  return j;
}


}  // namespace polydual
