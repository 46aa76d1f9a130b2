#include "split/cuts.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <deque>
#include <numeric>
#include <utility>

#include "predicates/predicates.h"

namespace polydual {

const char* cut_cause_name(CutCause c) {
  switch (c) {
    case CutCause::None: return "none";
    case CutCause::FreeEdge: return "free_edge";
    case CutCause::SheetCrossing: return "sheet_crossing";
    case CutCause::ConcaveEdge: return "concave_edge";
    case CutCause::ConcaveVertex: return "concave_vertex";
    case CutCause::Other: return "invalid_after_optimisation";
  }
  return "none";
}

namespace {

// v's star as the generators see it: tets (vertex_tets order) and, per tet
// face through v (4 slots per tet, the slot opposite v unused), the triangle,
// the neighbour's star index (-1: none) and whether the face is cut (model
// face or in the cut set being built).
struct Star {
  VertexId v;
  std::span<const TetId> tets;
  std::vector<TriId> tri;          // 4 per tet
  std::vector<std::int32_t> nb;    // 4 per tet, star index of the neighbour or -1
  std::vector<char> model, cut;    // 4 per tet
  std::vector<std::int8_t> apex;   // local index of v in each tet

  Star(const ClassifiedTetMesh& m, VertexId vv) : v(vv), tets(m.vertex_tets(vv)) {
    const std::size_t n = tets.size();
    tri.assign(4 * n, TriId::invalid());
    nb.assign(4 * n, -1);
    model.assign(4 * n, 0);
    cut.assign(4 * n, 0);
    apex.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const TetId t = tets[k];
      apex[k] = std::int8_t(m.local_index(t, v));
      for (int i = 0; i < 4; ++i) {
        if (i == apex[k]) continue;
        const TriId f = m.tet_triangle(t, i);
        tri[4 * k + i] = f;
        model[4 * k + i] = m.on_model_face(f);
        const TetId o = m.tet_neighbor(t, i);
        if (o.valid()) nb[4 * k + i] = std::int32_t(m.star_rank(v, o));
      }
    }
  }
  // Face slots through v of tet k (the three i != apex).
  template <class F>
  void for_faces(std::size_t k, F&& f) const {
    for (int i = 0; i < 4; ++i)
      if (i != apex[k]) f(i, 4 * k + std::size_t(i));
  }
  bool joins(std::size_t slot) const { return nb[slot] >= 0 && !model[slot] && !cut[slot]; }
  // Marks the triangle at slot (k, i) cut on both of its tets.
  void mark_cut(std::size_t slot) {
    cut[slot] = 1;
    const std::int32_t o = nb[slot];
    if (o < 0) return;
    for (int j = 0; j < 4; ++j)
      if (tri[4 * std::size_t(o) + j] == tri[slot]) cut[4 * std::size_t(o) + j] = 1;
  }
};

std::uint32_t find(std::vector<std::uint32_t>& p, std::uint32_t x) {
  while (p[x] != x) x = p[x] = p[p[x]];
  return x;
}

// Component label per star tet, 0-based in order of first appearance.
std::vector<std::uint32_t> components(const Star& s) {
  const std::size_t n = s.tets.size();
  std::vector<std::uint32_t> p(n);
  std::iota(p.begin(), p.end(), 0u);
  for (std::size_t k = 0; k < n; ++k)
    s.for_faces(k, [&](int, std::size_t slot) {
      if (s.joins(slot)) p[find(p, std::uint32_t(k))] = find(p, std::uint32_t(s.nb[slot]));
    });
  std::vector<std::uint32_t> label(n), root_label(n, ~0u);
  std::uint32_t next = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t r = find(p, std::uint32_t(k));
    if (root_label[r] == ~0u) root_label[r] = next++;
    label[k] = root_label[r];
  }
  return label;
}

// Cuts every joining face whose two tets have different labels.
void cut_between(Star& s, const std::vector<int>& label) {
  for (std::size_t k = 0; k < s.tets.size(); ++k)
    s.for_faces(k, [&](int, std::size_t slot) {
      if (s.joins(slot) && label[k] != label[std::size_t(s.nb[slot])]) s.mark_cut(slot);
    });
}

// The cut triangles of the star as (v, triangle) pairs.
void collect(const Star& s, std::vector<std::pair<VertexId, TriId>>& out) {
  for (std::size_t slot = 0; slot < s.cut.size(); ++slot)
    if (s.cut[slot] && !s.model[slot]) out.emplace_back(s.v, s.tri[slot]);
}

// A slot of a model-face triangle whose two tets are in one component, or -1.
std::int64_t find_slit(const Star& s, const std::vector<std::uint32_t>& comp) {
  for (std::size_t k = 0; k < s.tets.size(); ++k)
    for (int i = 0; i < 4; ++i) {
      const std::size_t slot = 4 * k + std::size_t(i);
      if (i != s.apex[k] && s.model[slot] && s.nb[slot] >= 0 && comp[k] == comp[std::size_t(s.nb[slot])])
        return std::int64_t(slot);
    }
  return -1;
}

// The two vertices other than v of triangle f, in an order.
std::pair<VertexId, VertexId> link_edge(const ClassifiedTetMesh& m, TriId f, VertexId v) {
  const auto t = m.triangle(f);
  VertexId o[2];
  int n = 0;
  for (VertexId x : t)
    if (x != v) o[n++] = x;
  return {o[0], o[1]};
}

// Labels 1 / 2 of the tets on the two faces of the sheet through `first`
// (the model-face triangles at v in component c, oriented coherently by a
// walk along the sheet's link path from `first`), then grows the labels over
// component c by breadth-first search. Returns the label per star tet (0 off c).
std::vector<int> sheet_labels(const ClassifiedTetMesh& m, const Star& s, const std::vector<std::uint32_t>& comp,
                              std::size_t first) {
  const std::uint32_t c = comp[first / 4];
  const std::size_t n = s.tets.size();
  // Sheet triangles of c: slot of one of their tets, each triangle once.
  std::vector<std::size_t> sheet;
  std::vector<TriId> seen;
  for (std::size_t k = 0; k < n; ++k)
    s.for_faces(k, [&](int, std::size_t slot) {
      if (!s.model[slot] || s.nb[slot] < 0 || comp[k] != c || comp[std::size_t(s.nb[slot])] != c) return;
      if (std::find(seen.begin(), seen.end(), s.tri[slot]) != seen.end()) return;
      seen.push_back(s.tri[slot]);
      sheet.push_back(slot);
    });
  // Coherent orientation: (a, b) for triangle (v, a, b); a neighbour sharing
  // b is oriented (b, x), one sharing a is oriented (x, a).
  std::vector<std::pair<VertexId, VertexId>> orient(sheet.size());
  std::vector<char> done(sheet.size(), 0);
  std::size_t start = 0;
  for (std::size_t i = 0; i < sheet.size(); ++i)
    if (s.tri[sheet[i]] == s.tri[first]) start = i;
  std::deque<std::size_t> queue;
  auto visit_from = [&](std::size_t i) {
    done[i] = 1;
    queue.push_back(i);
    while (!queue.empty()) {
      const std::size_t a = queue.front();
      queue.pop_front();
      for (std::size_t b = 0; b < sheet.size(); ++b) {
        if (done[b]) continue;
        const auto [x, y] = link_edge(m, s.tri[sheet[b]], s.v);
        const auto [p, q] = orient[a];
        std::pair<VertexId, VertexId> o;
        if (x == q) o = {x, y};
        else if (y == q) o = {y, x};
        else if (y == p) o = {x, y};
        else if (x == p) o = {y, x};
        else continue;
        orient[b] = o;
        done[b] = 1;
        queue.push_back(b);
      }
    }
  };
  orient[start] = link_edge(m, s.tri[sheet[start]], s.v);
  visit_from(start);
  for (std::size_t i = 0; i < sheet.size(); ++i)
    if (!done[i]) {
      orient[i] = link_edge(m, s.tri[sheet[i]], s.v);
      visit_from(i);
    }
  // Seeds by the exact side of each tet against its oriented sheet triangle;
  // the triangle `first` is seeded first so that its tets always differ.
  std::vector<int> label(n, 0);
  std::deque<std::size_t> front;
  auto seed = [&](std::size_t i) {
    const std::size_t slot = sheet[i];
    const std::size_t k0 = slot / 4, k1 = std::size_t(s.nb[slot]);
    for (std::size_t k : {k0, k1}) {
      if (label[k] != 0) continue;
      const auto& t = m.tet(s.tets[k]);
      VertexId d = VertexId::invalid();
      for (VertexId x : t)
        if (x != s.v && x != orient[i].first && x != orient[i].second) d = x;
      const Sign sg = orient3d(m.point(s.v), m.point(orient[i].first), m.point(orient[i].second), m.point(d));
      label[k] = sg == Sign::Positive ? 1 : 2;
      front.push_back(k);
    }
    if (label[k0] == label[k1]) label[k1] = 3 - label[k0];  // degenerate tets only
  };
  seed(start);
  for (std::size_t i = 0; i < sheet.size(); ++i)
    if (i != start) seed(i);
  while (!front.empty()) {
    const std::size_t k = front.front();
    front.pop_front();
    s.for_faces(k, [&](int, std::size_t slot) {
      if (!s.joins(slot)) return;
      const std::size_t o = std::size_t(s.nb[slot]);
      if (label[o] == 0) {
        label[o] = label[k];
        front.push_back(o);
      }
    });
  }
  // Tets outside c keep distinct labels of their own so that nothing there is cut.
  for (std::size_t k = 0; k < n; ++k)
    if (comp[k] != c) label[k] = 4 + int(comp[k]);
  return label;
}

// Free-edge cuts of one vertex; false when v has no slit side.
bool free_edge_star(const ClassifiedTetMesh& m, Star& s) {
  bool any = false;
  for (;;) {
    const std::vector<std::uint32_t> comp = components(s);
    const std::int64_t slit = find_slit(s, comp);
    if (slit < 0) return any;
    cut_between(s, sheet_labels(m, s, comp, std::size_t(slit)));
    any = true;
  }
}

// Model face planes at v: per model face tag, its lowest-numbered triangle at v.
std::vector<TriId> face_planes(const ClassifiedTetMesh& m, const Star& s) {
  std::vector<std::pair<std::int32_t, TriId>> best;
  for (std::size_t slot = 0; slot < s.tri.size(); ++slot) {
    if (!s.model[slot]) continue;
    const std::int32_t tag = m.triangle_class(s.tri[slot]).tag;
    auto it = std::find_if(best.begin(), best.end(), [&](const auto& b) { return b.first == tag; });
    if (it == best.end()) best.emplace_back(tag, s.tri[slot]);
    else if (s.tri[slot].idx < it->second.idx) it->second = s.tri[slot];
  }
  std::sort(best.begin(), best.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<TriId> out;
  for (const auto& b : best) out.push_back(b.second);
  return out;
}

int sign_value(Sign s) { return s == Sign::Positive ? 1 : s == Sign::Negative ? -1 : 0; }

// Whether a model-face triangle passes through v (read from the tets, without
// building the star: most vertices have none, and no free edge then).
bool touches_model_face(const ClassifiedTetMesh& m, VertexId v) {
  for (TetId t : m.vertex_tets(v)) {
    const int apex = m.local_index(t, v);
    for (int i = 0; i < 4; ++i)
      if (i != apex && m.on_model_face(m.tet_triangle(t, i))) return true;
  }
  return false;
}

}  // namespace

std::vector<std::uint32_t> star_sides(const ClassifiedTetMesh& m, VertexId v, const VertexCuts* cuts) {
  Star s(m, v);
  if (cuts)
    for (std::size_t slot = 0; slot < s.tri.size(); ++slot)
      if (s.tri[slot].valid() && cuts->cuts(v, s.tri[slot])) s.cut[slot] = 1;
  return components(s);
}

VertexCuts free_edge_cuts(const ClassifiedTetMesh& m, std::vector<VertexId>* slit) {
  // Independent per vertex: fixed blocks in parallel, joined in vertex order
  // (the same pairs and slit list for any thread count).
  constexpr std::size_t kBlock = 4096;
  const std::size_t nv = m.num_vertices(), nb = (nv + kBlock - 1) / kBlock;
  std::vector<std::vector<std::pair<VertexId, TriId>>> block_pairs(nb);
  std::vector<std::vector<VertexId>> block_slit(nb);
  tbb::parallel_for(std::size_t{0}, nb, [&](std::size_t b) {
    for (std::size_t vi = b * kBlock; vi < std::min(nv, (b + 1) * kBlock); ++vi) {
      if (!touches_model_face(m, VertexId(vi))) continue;
      Star s(m, VertexId(vi));
      if (!free_edge_star(m, s)) continue;
      collect(s, block_pairs[b]);
      block_slit[b].push_back(VertexId(vi));
    }
  });
  std::vector<std::pair<VertexId, TriId>> pairs;
  if (slit) slit->clear();
  for (std::size_t b = 0; b < nb; ++b) {
    pairs.insert(pairs.end(), block_pairs[b].begin(), block_pairs[b].end());
    if (slit) slit->insert(slit->end(), block_slit[b].begin(), block_slit[b].end());
  }
  return VertexCuts::from_pairs(nv, std::move(pairs));
}

VertexCuts plane_cuts(const ClassifiedTetMesh& m, std::span<const VertexId> vertices) {
  std::vector<std::pair<VertexId, TriId>> pairs;
  for (VertexId v : vertices) {
    Star s(m, v);
    const std::vector<TriId> planes = face_planes(m, s);
    if (planes.empty()) continue;
    // Label: base-3 digits of the tet's side of each plane (at most 19 planes enter the label, so the code fits
    // an int; more faces at one vertex are not met in practice).
    std::vector<int> label(s.tets.size(), 0);
    for (std::size_t k = 0; k < s.tets.size(); ++k) {
      const auto& t = m.tet(s.tets[k]);
      int code = 0;
      for (std::size_t p = 0; p < planes.size() && p < 19; ++p) {
        const auto [a, b, c] = m.triangle(planes[p]);
        int sum = 0;
        for (VertexId x : t)
          if (x != v) sum += sign_value(orient3d(m.point(a), m.point(b), m.point(c), m.point(x)));
        code = 3 * code + (sum > 0 ? 1 : sum < 0 ? 2 : 0);
      }
      label[k] = code;
    }
    cut_between(s, label);
    collect(s, pairs);
  }
  return VertexCuts::from_pairs(m.num_vertices(), std::move(pairs));
}

VertexCuts fallback_cuts(const ClassifiedTetMesh& m, std::span<const VertexId> vertices) {
  std::vector<std::pair<VertexId, TriId>> pairs;
  for (VertexId v : vertices) {
    const Star s(m, v);
    for (std::size_t slot = 0; slot < s.tri.size(); ++slot)
      if (s.tri[slot].valid() && !s.model[slot] && s.nb[slot] >= 0) pairs.emplace_back(v, s.tri[slot]);
  }
  VertexCuts c = VertexCuts::from_pairs(m.num_vertices(), std::move(pairs));
  if (!vertices.empty()) {
    c.whole.assign(m.num_vertices(), 0);
    for (VertexId v : vertices) c.whole[v.idx] = 1;
  }
  return c;
}

VertexCuts with_whole_cuts(const ClassifiedTetMesh& m, const VertexCuts& free, std::span<const char> whole) {
  std::vector<VertexId> marked;
  for (std::size_t v = 0; v < whole.size(); ++v)
    if (whole[v]) marked.push_back(VertexId(v));
  return VertexCuts::merged(m.num_vertices(), free, fallback_cuts(m, marked));
}

CutCause invalid_cause(const ClassifiedTetMesh& m, VertexId v) {
  const int dim = m.vertex_class(v).dim;
  if (dim == 0) return CutCause::ConcaveVertex;
  if (dim != 1) return CutCause::Other;
  const Star s(m, v);
  return face_planes(m, s).size() >= 3 ? CutCause::SheetCrossing : CutCause::ConcaveEdge;
}

}  // namespace polydual
