#include "mesh/classified_tet_mesh.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"

namespace polydual {

namespace {
// Outward-oriented local faces of a positive tet: face i is opposite vertex i.
constexpr int kTetFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

constexpr bool even_permutation(int a, int b, int c, int d) {
  int p[4] = {a, b, c, d}, inv = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inv += p[i] > p[j];
  return inv % 2 == 0;
}

// For local indices ia, ib of an edge, the other two local indices (ic, id) such
// that (ia, ib, ic, id) is an even permutation: going around ia->ib right-handedly
// inside the tet leads from ic to id. Tabulated: this sits in the edge-ring walk.
struct RingTable {
  std::int8_t c[4][4], d[4][4];
  constexpr RingTable() : c{}, d{} {
    for (int ia = 0; ia < 4; ++ia)
      for (int ib = 0; ib < 4; ++ib) {
        if (ia == ib) continue;
        int o[2] = {0, 0}, n = 0;
        for (int i = 0; i < 4; ++i)
          if (i != ia && i != ib) o[n++] = i;
        const bool even = even_permutation(ia, ib, o[0], o[1]);
        c[ia][ib] = static_cast<std::int8_t>(even ? o[0] : o[1]);
        d[ia][ib] = static_cast<std::int8_t>(even ? o[1] : o[0]);
      }
  }
};
constexpr RingTable kRing;

inline void ring_others(int ia, int ib, int& ic, int& id) {
  ic = kRing.c[ia][ib];
  id = kRing.d[ia][ib];
}

}  // namespace

const ModelEntity* ModelTopology::find(int dim, std::int32_t tag) const {
  const auto& v = entities[dim];
  auto it = std::lower_bound(v.begin(), v.end(), tag,
                             [](const ModelEntity& e, std::int32_t t) { return e.tag < t; });
  return (it != v.end() && it->tag == tag) ? &*it : nullptr;
}

int ClassifiedTetMesh::local_index(TetId t, VertexId v) const {
  const auto& tv = tets_[t.idx];
  for (int i = 0; i < 4; ++i)
    if (tv[i] == v) return i;
  return -1;
}

EdgeId ClassifiedTetMesh::find_edge(VertexId a, VertexId b) const {
  for (TetId t : vertex_tets(a)) {
    int ia = local_index(t, a), ib = local_index(t, b);
    if (ib < 0) continue;
    for (int k = 0; k < 6; ++k)
      if ((kTetEdge[k][0] == ia && kTetEdge[k][1] == ib) ||
          (kTetEdge[k][0] == ib && kTetEdge[k][1] == ia))
        return tet_edge(t, k);
  }
  return EdgeId::invalid();
}

std::vector<TetId> ClassifiedTetMesh::edge_ring(EdgeId e, bool* closed) const {
  std::vector<TetId> tets;
  std::vector<TriId> tris;
  bool c;
  edge_ring(e, tets, tris, c);
  if (closed) *closed = c;
  return tets;
}

void ClassifiedTetMesh::edge_ring(EdgeId e, std::vector<TetId>& tets, std::vector<TriId>& tris,
                                  bool& closed) const {
  // Walk forwards from the stored tet, across the face after each tet
  // (a, b, id); a closed ring comes back to the start. An open ring hits the
  // boundary: then walk backwards from the start (across (a, b, ic)) and put
  // that part in front, so the ring starts at the boundary.
  const VertexId a = edge_verts_[e.idx][0], b = edge_verts_[e.idx][1];
  const TetId start = edge_tet_[e.idx];
  tets.clear();
  tris.clear();
  int ic, id;
  ring_others(local_index(start, a), local_index(start, b), ic, id);
  const TriId before_start = tet_triangle(start, id);
  const TetId before_tet = tet_neighbor(start, id);
  tris.push_back(before_start);
  TetId t = start;
  for (;;) {
    tets.push_back(t);
    tris.push_back(tet_triangle(t, ic));
    const TetId next = tet_neighbor(t, ic);
    if (!next.valid() || next == start) { closed = next.valid(); break; }
    t = next;
    ring_others(local_index(t, a), local_index(t, b), ic, id);
  }
  if (closed || !before_tet.valid()) return;
  // Open ring with tets before the start: collect them backwards.
  std::vector<TetId> back_tets;
  std::vector<TriId> back_tris;
  for (TetId prev = before_tet; prev.valid();) {
    ring_others(local_index(prev, a), local_index(prev, b), ic, id);
    back_tets.push_back(prev);
    back_tris.push_back(tet_triangle(prev, id));
    prev = tet_neighbor(prev, id);
  }
  tets.insert(tets.begin(), back_tets.rbegin(), back_tets.rend());
  tris.insert(tris.begin(), back_tris.rbegin(), back_tris.rend());
}

EdgeId ClassifiedTetMesh::triangle_edge(TriId f, VertexId a, VertexId b) const {
  TetId t = tri_tets_[f.idx][0];
  int ia = local_index(t, a), ib = local_index(t, b);
  for (int k = 0; k < 6; ++k)
    if ((kTetEdge[k][0] == ia && kTetEdge[k][1] == ib) || (kTetEdge[k][0] == ib && kTetEdge[k][1] == ia))
      return tet_edge(t, k);
  return EdgeId::invalid();
}

double ClassifiedTetMesh::tet_volume(TetId t) const {
  const auto& v = tets_[t.idx];
  Vec3 a = points_[v[0].idx];
  return dot(points_[v[1].idx] - a, cross(points_[v[2].idx] - a, points_[v[3].idx] - a)) / 6.0;
}

ClassifiedTetMesh TetMeshBuilder::build_topology(std::string source, std::vector<Point3> points,
                                                 std::vector<std::array<VertexId, 4>> tets,
                                                 std::vector<std::int32_t> regions,
                                                 std::vector<std::uint32_t> input_vertex,
                                                 std::vector<std::uint32_t> input_tet) {
  ClassifiedTetMesh m;
  m.source_ = std::move(source);
  m.points_ = std::move(points);
  m.tets_ = std::move(tets);
  m.tet_region_ = std::move(regions);
  const std::size_t nv = m.points_.size(), nt = m.tets_.size();
  m.input_vertex_ = std::move(input_vertex);
  m.input_tet_ = std::move(input_tet);
  if (m.input_vertex_.empty()) {
    m.input_vertex_.resize(nv);
    std::iota(m.input_vertex_.begin(), m.input_vertex_.end(), 0u);
  }
  if (m.input_tet_.empty()) {
    m.input_tet_.resize(nt);
    std::iota(m.input_tet_.begin(), m.input_tet_.end(), 0u);
  }
  auto tet_place = [&](std::size_t t) { return "tet " + std::to_string(m.input_tet_[t] + 1); };
  auto vnum = [&](std::size_t v) { return std::to_string(m.input_vertex_[v] + 1); };

  // Vertex stars (CSR, tets in increasing order).
  m.vstar_off_.assign(nv + 1, 0);
  for (const auto& t : m.tets_)
    for (VertexId v : t) ++m.vstar_off_[v.idx + 1];
  std::partial_sum(m.vstar_off_.begin(), m.vstar_off_.end(), m.vstar_off_.begin());
  m.vstar_.resize(4 * nt);
  {
    std::vector<std::uint32_t> fill(m.vstar_off_.begin(), m.vstar_off_.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
      for (VertexId v : m.tets_[t]) m.vstar_[fill[v.idx]++] = TetId(t);
  }

  // Face adjacency: bucket the 4nt tet faces by their smallest vertex, sort
  // each bucket by the other two, and pair equal keys (two at most).
  m.tet_adj_.assign(4 * nt, TetId::invalid());
  m.tet_tri_.assign(4 * nt, TriId::invalid());
  {
    struct FaceRec { std::uint32_t mid, max, code; };  // code = 4t + i
    std::vector<std::uint32_t> off(nv + 1, 0);
    auto sorted3 = [&](std::size_t t, int i, std::uint32_t& lo, std::uint32_t& mid, std::uint32_t& hi) {
      const auto& tv = m.tets_[t];
      std::uint32_t a = tv[kTetFace[i][0]].idx, b = tv[kTetFace[i][1]].idx, c = tv[kTetFace[i][2]].idx;
      if (a > b) std::swap(a, b);
      if (b > c) std::swap(b, c);
      if (a > b) std::swap(a, b);
      lo = a; mid = b; hi = c;
    };
    for (std::size_t t = 0; t < nt; ++t)
      for (int i = 0; i < 4; ++i) {
        std::uint32_t lo, mid, hi;
        sorted3(t, i, lo, mid, hi);
        ++off[lo + 1];
      }
    std::partial_sum(off.begin(), off.end(), off.begin());
    std::vector<FaceRec> recs(4 * nt);
    std::vector<std::uint32_t> fill(off.begin(), off.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
      for (int i = 0; i < 4; ++i) {
        std::uint32_t lo, mid, hi;
        sorted3(t, i, lo, mid, hi);
        recs[fill[lo]++] = {mid, hi, std::uint32_t(4 * t + i)};
      }
    for (std::size_t v = 0; v < nv; ++v) {
      auto first = recs.begin() + off[v], last = recs.begin() + off[v + 1];
      std::sort(first, last, [](const FaceRec& x, const FaceRec& y) {
        return x.mid != y.mid ? x.mid < y.mid : (x.max != y.max ? x.max < y.max : x.code < y.code);
      });
      for (auto it = first; it != last;) {
        auto jt = it + 1;
        while (jt != last && jt->mid == it->mid && jt->max == it->max) ++jt;
        const std::size_t n = std::size_t(jt - it);
        const std::uint32_t t = it->code / 4, ti = it->code % 4;
        if (n >= 2) {
          const std::uint32_t s2 = (it + 1)->code / 4, si = (it + 1)->code % 4;
          if (m.tets_[s2][si] == m.tets_[t][ti])
            throw InputError(m.source_, tet_place(s2),
                             "duplicated tet (same four vertices as " + tet_place(t) + ")");
          if (n > 2)
            throw InputError(m.source_, tet_place(t),
                             "non-conformal mesh: triangle (" + vnum(v) + ", " + vnum(it->mid) + ", " +
                                 vnum(it->max) + ") is shared by more than two tets (" +
                                 std::to_string(m.input_tet_[t] + 1) + ", " + std::to_string(m.input_tet_[s2] + 1) +
                                 ", " + std::to_string(m.input_tet_[(it + 2)->code / 4] + 1) + ")");
          m.tet_adj_[4 * t + ti] = TetId(s2);
          m.tet_adj_[4 * s2 + si] = TetId(t);
        }
        it = jt;
      }
    }
  }
  // Triangles, numbered in the order (tet, local face) of their first tet.
  for (std::size_t t = 0; t < nt; ++t) {
    for (int i = 0; i < 4; ++i) {
      if (m.tet_tri_[4 * t + i].valid()) continue;
      TriId f(m.tri_verts_.size());
      const auto& tv = m.tets_[t];
      m.tri_verts_.push_back({tv[kTetFace[i][0]], tv[kTetFace[i][1]], tv[kTetFace[i][2]]});
      TetId s = m.tet_adj_[4 * t + i];
      m.tri_tets_.push_back({TetId(t), s});
      m.tet_tri_[4 * t + i] = f;
      if (s.valid()) {
        for (int j = 0; j < 4; ++j)
          if (m.tet_adj_[4 * s.idx + j] == TetId(t)) m.tet_tri_[4 * s.idx + j] = f;
      }
    }
  }
  // Edges: numbered by (lower vertex, higher vertex). Bucket the 6nt tet edges
  // by their lower vertex and sort each bucket by (higher vertex, 6t+k).
  {
    struct EdgeRec { std::uint32_t hi, code; };
    std::vector<std::uint32_t> off(nv + 1, 0);
    for (std::size_t t = 0; t < nt; ++t)
      for (int k = 0; k < 6; ++k)
        ++off[std::min(m.tets_[t][kTetEdge[k][0]].idx, m.tets_[t][kTetEdge[k][1]].idx) + 1];
    std::partial_sum(off.begin(), off.end(), off.begin());
    std::vector<EdgeRec> recs(6 * nt);
    std::vector<std::uint32_t> fill(off.begin(), off.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
      for (int k = 0; k < 6; ++k) {
        std::uint32_t a = m.tets_[t][kTetEdge[k][0]].idx, b = m.tets_[t][kTetEdge[k][1]].idx;
        if (a > b) std::swap(a, b);
        recs[fill[a]++] = {b, std::uint32_t(6 * t + k)};
      }
    m.tet_edge_.resize(6 * nt);
    m.edge_verts_.reserve(6 * nt / 4);
    m.edge_tet_.reserve(6 * nt / 4);
    for (std::size_t v = 0; v < nv; ++v) {
      auto first = recs.begin() + off[v], last = recs.begin() + off[v + 1];
      std::sort(first, last, [](const EdgeRec& x, const EdgeRec& y) {
        return x.hi != y.hi ? x.hi < y.hi : x.code < y.code;
      });
      for (auto it = first; it != last; ++it) {
        if (it == first || it->hi != (it - 1)->hi) {
          m.edge_verts_.push_back({VertexId(v), VertexId(it->hi)});
          m.edge_tet_.push_back(TetId(it->code / 6));
        }
        m.tet_edge_[it->code] = EdgeId(m.edge_verts_.size() - 1);
      }
    }
  }
  m.vertex_class_.assign(nv, ModelRef{});
  m.edge_class_.assign(m.edge_verts_.size(), ModelRef{});
  m.tri_class_.assign(m.tri_verts_.size(), ModelRef{});
  return m;
}

}  // namespace polydual
