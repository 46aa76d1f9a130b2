// Virtual cut surfaces (design §8, "every cell valid"): per primal vertex v, a
// set of interior triangles through v (on no model face) that cut v's star
// only, as if they were on a model face for v and for no other vertex. The
// dual builder then gives v one cell per side of its star cut by the model
// faces and by these triangles, and keeps the neighbouring cells closed by
// inserting the new points into their faces (build_dual.h). The split stage
// (lib/split) decides which vertices get which cuts.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/handles.h"

namespace polydual {

struct VertexCuts {
  // CSR over the primal vertices (ClassifiedTetMesh's internal numbering):
  // tri[off[v] .. off[v+1]) are the cut triangles of v, increasing, each
  // containing v and on no model face. Empty `off`: no cuts at all.
  std::vector<std::uint32_t> off;
  std::vector<TriId> tri;
  // Per vertex (empty: none): v is cut whole, at every interior triangle of
  // its star (split/cuts.h fallback_cuts), so it has one cell per tet (or,
  // once the split has coarsened it, split/coarsen.h, at the triangles
  // between classes of tets: one cell per class, the union of its corners;
  // every interior triangle through v keeps its centre either way). The
  // points of such a star (centres of the tets and triangles through v, the
  // midpoints of its edges, v itself) are placed at the barycentres of their
  // entities, never merged or collapsed, and every edge of v is a stop edge:
  // each cell of v is then the barycentric region {x in t : lambda_v(x) >=
  // lambda_w(x) for every vertex w of t}, a convex polytope with planar faces
  // (proofs/dual_cuts.md, C5), whatever the neighbours' points.
  std::vector<char> whole;

  bool is_whole(VertexId v) const { return v.idx < whole.size() && whole[v.idx] != 0; }
  bool any_whole() const { return std::find(whole.begin(), whole.end(), char(1)) != whole.end(); }
  bool empty() const { return tri.empty() && !any_whole(); }
  std::span<const TriId> of(VertexId v) const {
    if (off.empty()) return {};
    return {tri.data() + off[v.idx], tri.data() + off[v.idx + 1]};
  }
  bool cuts(VertexId v, TriId f) const {
    const std::span<const TriId> s = of(v);
    return std::binary_search(s.begin(), s.end(), f, [](TriId a, TriId b) { return a.idx < b.idx; });
  }
  std::size_t num_vertices_cut() const {
    std::size_t n = 0;
    for (std::size_t v = 0; v + 1 < off.size(); ++v) n += off[v + 1] > off[v];
    return n;
  }

  // From (vertex, triangle) pairs in any order (duplicates dropped), for a
  // mesh of num_vertices vertices.
  static VertexCuts from_pairs(std::size_t num_vertices, std::vector<std::pair<VertexId, TriId>> pairs) {
    std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
      return a.first.idx != b.first.idx ? a.first.idx < b.first.idx : a.second.idx < b.second.idx;
    });
    pairs.erase(std::unique(pairs.begin(), pairs.end(),
                            [](const auto& a, const auto& b) { return a.first == b.first && a.second == b.second; }),
                pairs.end());
    VertexCuts c;
    c.off.assign(num_vertices + 1, 0);
    for (const auto& p : pairs) ++c.off[p.first.idx + 1];
    for (std::size_t v = 0; v < num_vertices; ++v) c.off[v + 1] += c.off[v];
    c.tri.reserve(pairs.size());
    for (const auto& p : pairs) c.tri.push_back(p.second);
    return c;
  }
  // The union of two cut sets of one mesh (a vertex is whole if it is in either).
  static VertexCuts merged(std::size_t num_vertices, const VertexCuts& a, const VertexCuts& b) {
    std::vector<std::pair<VertexId, TriId>> pairs;
    for (const VertexCuts* c : {&a, &b})
      for (std::size_t v = 0; v + 1 < c->off.size(); ++v)
        for (TriId f : c->of(VertexId(v))) pairs.emplace_back(VertexId(v), f);
    VertexCuts out = from_pairs(num_vertices, std::move(pairs));
    if (a.any_whole() || b.any_whole()) {
      out.whole.assign(num_vertices, 0);
      for (std::size_t v = 0; v < num_vertices; ++v) out.whole[v] = char(a.is_whole(VertexId(v)) || b.is_whole(VertexId(v)));
    }
    return out;
  }
};

}  // namespace polydual
