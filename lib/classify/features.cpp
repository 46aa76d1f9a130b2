// Feature edges: sharp edges grouped into chains, chains judged as lines
// (lib/classify/features.h). Double geometry throughout (angle thresholds).
#include "classify/features.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/union_find.h"

namespace polydual {

double angle_deg(const Vec3& u, const Vec3& v) {
  const double d = norm(u) * norm(v);
  if (d == 0) return 0;
  return std::acos(std::clamp(dot(u, v) / d, -1.0, 1.0)) * 180.0 / M_PI;
}

namespace {

// Two sharp edges continue one feature line through their common vertex v:
// the line turns by at most the strong angle (a sharper turn is a corner,
// which ends lines), the bend keeps its sign (both convex or both concave),
// and the two sides stay the same sheets: one side's normal turns by at most
// the feature angle, the other's by at most the feature angle plus the
// line's turn (a rim of a coarse cylinder: the cap is flat, the side's
// normal turns with the rim). A zigzag across a coarse curved surface swaps
// or twists its sides and fails.
bool continues(const BendEdge& in, const BendEdge& out, std::uint32_t v, const FeatureRule& rule) {
  if (norm2(in.left) == 0 || norm2(out.left) == 0) return false;
  const bool in_fwd = in.b == v, out_fwd = out.a == v;  // directed into v, then out of v
  const Vec3 di = in_fwd ? in.dir : -1.0 * in.dir, dout = out_fwd ? out.dir : -1.0 * out.dir;
  const Vec3 li = in_fwd ? in.left : in.right, ri = in_fwd ? in.right : in.left;
  const Vec3 lo = out_fwd ? out.left : out.right, ro = out_fwd ? out.right : out.left;
  const double turn = angle_deg(di, dout);
  if (turn > rule.strong_deg) return false;
  if ((dot(cross(li, ri), di) > 0) != (dot(cross(lo, ro), dout) > 0)) return false;
  const double left = angle_deg(li, lo), right = angle_deg(ri, ro);
  return std::min(left, right) <= rule.feature_deg && std::max(left, right) <= rule.feature_deg + turn;
}

// The sharp edges at each vertex: (vertex, edge) pairs sorted by vertex.
std::vector<std::pair<std::uint32_t, std::uint32_t>> sharp_incidences(const std::vector<BendEdge>& edges,
                                                                      const std::vector<FeatureVerdict>& out) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> inc;
  for (std::uint32_t i = 0; i < edges.size(); ++i) {
    if (out[i] == FeatureVerdict::Smooth) continue;
    inc.emplace_back(edges[i].a, i);
    inc.emplace_back(edges[i].b, i);
  }
  std::sort(inc.begin(), inc.end());
  return inc;
}

// Chains: sharp edges linked at vertices with exactly two sharp edges that
// continue each other. linked[2 i + s] says whether edge i is linked at its
// end s (0: a, 1: b).
struct Chains {
  UnionFind uf;
  std::vector<char> linked;
  explicit Chains(std::size_t n) : uf(n), linked(2 * n, 0) {}
};

Chains link_chains(const std::vector<BendEdge>& edges,
                   const std::vector<std::pair<std::uint32_t, std::uint32_t>>& inc, const FeatureRule& rule) {
  Chains ch(edges.size());
  for (std::size_t k = 0; k < inc.size();) {
    std::size_t n = 1;
    while (k + n < inc.size() && inc[k + n].first == inc[k].first) ++n;
    const std::uint32_t v = inc[k].first;
    if (n == 2) {
      const std::uint32_t i = inc[k].second, j = inc[k + 1].second;
      if (continues(edges[i], edges[j], v, rule)) {
        ch.uf.unite(i, j);
        ch.linked[2 * i + (edges[i].b == v)] = 1;
        ch.linked[2 * j + (edges[j].b == v)] = 1;
      }
    }
    k += n;
  }
  return ch;
}

// FE1(ii): per chain root, kept for its length, or for a strong edge in a
// chain of two or more.
std::vector<char> kept_by_length(const std::vector<FeatureVerdict>& out, Chains& ch, const FeatureRule& rule) {
  const std::size_t n = out.size();
  std::vector<std::uint32_t> size(n, 0);
  std::vector<char> strong(n, 0), kept(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (out[i] == FeatureVerdict::Smooth) continue;
    const std::uint32_t r = ch.uf.find(i);
    ++size[r];
    strong[r] |= out[i] == FeatureVerdict::Strong;
  }
  for (std::size_t r = 0; r < n; ++r) kept[r] = size[r] >= rule.min_chain_edges || (strong[r] && size[r] >= 2);
  return kept;
}

// The first entry of vertex v in a list sorted by vertex.
template <class T>
typename std::vector<std::pair<std::uint32_t, T>>::const_iterator first(
    const std::vector<std::pair<std::uint32_t, T>>& list, std::uint32_t v) {
  return std::lower_bound(list.begin(), list.end(), v, [](const auto& x, std::uint32_t y) { return x.first < y; });
}

// FE1(iii): where a short chain's free end may stop: at a chain kept by
// length, or at a corner (three sharp edges, two of them strong, every smooth
// edge there within half the feature angle: flat sectors).
class Anchors {
 public:
  Anchors(const std::vector<BendEdge>& edges, const std::vector<FeatureVerdict>& out,
          const std::vector<std::pair<std::uint32_t, std::uint32_t>>& inc, Chains& ch, const std::vector<char>& kept,
          const FeatureRule& rule)
      : out_(out), inc_(inc), half_feature_(rule.feature_deg / 2) {
    for (const BendEdge& e : edges)
      if (e.bend <= rule.feature_deg) {
        smooth_bend_.emplace_back(e.a, e.bend);
        smooth_bend_.emplace_back(e.b, e.bend);
      }
    std::sort(smooth_bend_.begin(), smooth_bend_.end());
    for (const auto& [v, i] : inc)
      if (kept[ch.uf.find(i)]) kept_at_.emplace_back(v, ch.uf.find(i));  // sorted by vertex, as inc
  }

  // v ends the chain `root` at a kept chain or a corner.
  bool anchors(std::uint32_t v, std::uint32_t root) const {
    for (auto it = first(kept_at_, v); it != kept_at_.end() && it->first == v; ++it)
      if (it->second != root) return true;
    std::size_t sharp = 0, strong = 0;
    for (auto it = first(inc_, v); it != inc_.end() && it->first == v; ++it) {
      ++sharp;
      strong += out_[it->second] == FeatureVerdict::Strong;
    }
    if (sharp < 3 || strong < 2) return false;
    for (auto it = first(smooth_bend_, v); it != smooth_bend_.end() && it->first == v; ++it)
      if (it->second > half_feature_) return false;
    return true;
  }

 private:
  const std::vector<FeatureVerdict>& out_;
  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& inc_;
  double half_feature_;
  std::vector<std::pair<std::uint32_t, double>> smooth_bend_;       // (vertex, bend), sorted
  std::vector<std::pair<std::uint32_t, std::uint32_t>> kept_at_;    // (vertex, kept chain root)
};

}  // namespace

// FE1: sharp edges, linked into chains; chains kept by length or a strong
// edge (ii), or by both free ends at kept chains or corners (iii); the rest
// is noise.
std::vector<FeatureVerdict> select_feature_edges(const std::vector<BendEdge>& edges, const FeatureRule& rule) {
  const std::size_t n = edges.size();
  std::vector<FeatureVerdict> out(n, FeatureVerdict::Smooth);
  for (std::size_t i = 0; i < n; ++i)
    if (edges[i].bend > rule.strong_deg) out[i] = FeatureVerdict::Strong;
    else if (edges[i].bend > rule.feature_deg) out[i] = FeatureVerdict::Noise;
  const auto inc = sharp_incidences(edges, out);
  Chains ch = link_chains(edges, inc, rule);
  const std::vector<char> kept = kept_by_length(out, ch, rule);
  const Anchors anchors(edges, out, inc, ch, kept, rule);
  std::vector<char> joins(n, 1);  // per root of a chain not kept by length: every free end anchored
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t r = ch.uf.find(i);
    if (out[i] == FeatureVerdict::Smooth || kept[r]) continue;
    if (!ch.linked[2 * i] && !anchors.anchors(edges[i].a, r)) joins[r] = 0;
    if (!ch.linked[2 * i + 1] && !anchors.anchors(edges[i].b, r)) joins[r] = 0;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (out[i] == FeatureVerdict::Smooth) continue;
    const std::uint32_t r = ch.uf.find(i);
    if (!kept[r] && !joins[r]) out[i] = FeatureVerdict::Noise;
    else if (out[i] == FeatureVerdict::Noise) out[i] = FeatureVerdict::Chain;
  }
  return out;
}

}  // namespace polydual
