#include "mesh/classified_tet_mesh.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"

namespace polydual {

namespace {
// Outward-oriented local faces of a positive tet: face i is opposite vertex i.
constexpr int kTetFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

using detail::kRing;
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
  // Open ring with tets before the start: append them backwards, then move
  // them to the front in ring order (no temporary vectors).
  const std::size_t n_tets = tets.size(), n_tris = tris.size();
  for (TetId prev = before_tet; prev.valid();) {
    ring_others(local_index(prev, a), local_index(prev, b), ic, id);
    tets.push_back(prev);
    tris.push_back(tet_triangle(prev, id));
    prev = tet_neighbor(prev, id);
  }
  std::reverse(tets.begin() + std::ptrdiff_t(n_tets), tets.end());
  std::rotate(tets.begin(), tets.begin() + std::ptrdiff_t(n_tets), tets.end());
  std::reverse(tris.begin() + std::ptrdiff_t(n_tris), tris.end());
  std::rotate(tris.begin(), tris.begin() + std::ptrdiff_t(n_tris), tris.end());
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
  if (nt >= (std::size_t(1) << 30))
    throw InputError(m.source_, "", "more than 2^30 tets (" + std::to_string(nt) + ") are not supported");
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
  constexpr std::uint32_t kNoNeighbour = ClassifiedTetMesh::kNoNeighbour;
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

  // Face adjacency, one vertex v at a time. A tet face's smallest vertex is
  // the tet's smallest vertex (three faces) or, for the face opposite it, the
  // tet's second smallest: bucket the tets by both (counting sorts), collect
  // the faces of bucket v keyed by their two other vertices (one 64-bit key),
  // sort (stable insertion sort, the buckets are small) and pair equal keys
  // (two at most).
  m.tet_adj_.assign(4 * nt, kNoNeighbour);
  m.tet_tri_.assign(4 * nt, TriId::invalid());
  std::size_t num_tris = 0;
  {
    // low[t]: local index of t's smallest vertex; second[t]: of its second smallest.
    std::vector<std::uint8_t> low(nt), second(nt);
    std::vector<std::uint32_t> off1(nv + 1, 0), off2(nv + 1, 0);
    for (std::size_t t = 0; t < nt; ++t) {
      const auto& tv = m.tets_[t];
      int l = 0;
      for (int i = 1; i < 4; ++i) l = tv[i].idx < tv[l].idx ? i : l;
      int s2 = l == 0 ? 1 : 0;
      for (int i = 0; i < 4; ++i) s2 = (i != l && tv[i].idx < tv[s2].idx) ? i : s2;
      low[t] = std::uint8_t(l);
      second[t] = std::uint8_t(s2);
      ++off1[tv[l].idx + 1];
      ++off2[tv[s2].idx + 1];
    }
    std::partial_sum(off1.begin(), off1.end(), off1.begin());
    std::partial_sum(off2.begin(), off2.end(), off2.begin());
    std::vector<std::uint32_t> by_low(nt), by_second(nt);
    {
      std::vector<std::uint32_t> f1(off1.begin(), off1.end() - 1), f2(off2.begin(), off2.end() - 1);
      for (std::size_t t = 0; t < nt; ++t) {
        by_low[f1[m.tets_[t][low[t]].idx]++] = std::uint32_t(t);
        by_second[f2[m.tets_[t][second[t]].idx]++] = std::uint32_t(t);
      }
    }
    struct FaceRec { std::uint64_t key; std::uint32_t code; };  // key = mid << 32 | max, code = 4t + i
    std::vector<FaceRec> recs;
    auto push_face = [&](std::uint32_t t, int i) {
      const auto& tv = m.tets_[t];
      std::uint32_t a = tv[kTetFace[i][0]].idx, b = tv[kTetFace[i][1]].idx, c = tv[kTetFace[i][2]].idx;
      if (a > b) std::swap(a, b);
      if (b > c) std::swap(b, c);
      if (a > b) std::swap(a, b);
      recs.push_back({std::uint64_t(b) << 32 | c, 4 * t + std::uint32_t(i)});
    };
    for (std::size_t v = 0; v < nv; ++v) {
      recs.clear();
      for (std::uint32_t k = off1[v]; k < off1[v + 1]; ++k) {
        const std::uint32_t t = by_low[k];
        for (int i = 0; i < 4; ++i)
          if (i != low[t]) push_face(t, i);
      }
      for (std::uint32_t k = off2[v]; k < off2[v + 1]; ++k) push_face(by_second[k], low[by_second[k]]);
      for (std::size_t i = 1; i < recs.size(); ++i) {
        const FaceRec r = recs[i];
        std::size_t j = i;
        for (; j > 0 && r.key < recs[j - 1].key; --j) recs[j] = recs[j - 1];
        recs[j] = r;
      }
      for (auto it = recs.begin(); it != recs.end();) {
        auto jt = it + 1;
        while (jt != recs.end() && jt->key == it->key) ++jt;
        const std::size_t n = std::size_t(jt - it);
        ++num_tris;
        if (n >= 2) {
          const std::uint32_t t = it->code / 4, ti = it->code % 4;
          const std::uint32_t s2 = (it + 1)->code / 4, si = (it + 1)->code % 4;
          if (m.tets_[s2][si] == m.tets_[t][ti])
            throw InputError(m.source_, tet_place(std::max(t, s2)),
                             "duplicated tet (same four vertices as " + tet_place(std::min(t, s2)) + ")");
          if (n > 2)
            throw InputError(m.source_, tet_place(t),
                             "non-conformal mesh: triangle (" + vnum(v) + ", " + vnum(it->key >> 32) + ", " +
                                 vnum(it->key & 0xffffffffu) + ") is shared by more than two tets (" +
                                 std::to_string(m.input_tet_[t] + 1) + ", " + std::to_string(m.input_tet_[s2] + 1) +
                                 ", " + std::to_string(m.input_tet_[(it + 2)->code / 4] + 1) + ")");
          m.tet_adj_[it->code] = (it + 1)->code;
          m.tet_adj_[(it + 1)->code] = it->code;
        }
        it = jt;
      }
    }
  }
  // Triangles, numbered in the order (tet, local face) of their first tet.
  m.tri_verts_.reserve(num_tris);
  m.tri_tets_.reserve(num_tris);
  for (std::size_t t = 0; t < nt; ++t) {
    for (int i = 0; i < 4; ++i) {
      if (m.tet_tri_[4 * t + i].valid()) continue;
      TriId f(m.tri_verts_.size());
      const auto& tv = m.tets_[t];
      m.tri_verts_.push_back({tv[kTetFace[i][0]], tv[kTetFace[i][1]], tv[kTetFace[i][2]]});
      const std::uint32_t across = m.tet_adj_[4 * t + i];
      m.tri_tets_.push_back({TetId(t), across == kNoNeighbour ? TetId::invalid() : TetId(across / 4)});
      m.tet_tri_[4 * t + i] = f;
      if (across != kNoNeighbour) m.tet_tri_[across] = f;
    }
  }
  // Edges, numbered in the order of their first (tet, local edge): an
  // unnumbered tet edge gets the next id, and a walk around its ring through
  // the face adjacency (both ways when the ring is open) gives every tet of
  // the ring the same id. Each tet edge is visited once.
  {
    static constexpr auto kEdgeOf = [] {  // local edge joining local vertices i and j
      std::array<std::array<std::int8_t, 4>, 4> e{};
      for (int k = 0; k < 6; ++k) {
        e[kTetEdge[k][0]][kTetEdge[k][1]] = std::int8_t(k);
        e[kTetEdge[k][1]][kTetEdge[k][0]] = std::int8_t(k);
      }
      return e;
    }();
    m.tet_edge_.assign(6 * nt, EdgeId::invalid());
    // Euler's relation for a ball: E = V + T + (boundary triangles)/2 - 1.
    const std::size_t ne_guess = nv + nt + (2 * num_tris - 4 * nt) / 2 + 16;
    m.edge_verts_.reserve(ne_guess);
    m.edge_tet_.reserve(ne_guess);
    for (std::size_t t = 0; t < nt; ++t) {
      for (int k = 0; k < 6; ++k) {
        if (m.tet_edge_[6 * t + k].valid()) continue;
        const EdgeId e(m.edge_verts_.size());
        const VertexId a = m.tets_[t][kTetEdge[k][0]], b = m.tets_[t][kTetEdge[k][1]];
        m.edge_verts_.push_back({std::min(a, b), std::max(a, b)});
        m.edge_tet_.push_back(TetId(t));
        m.tet_edge_[6 * t + k] = e;
        // Walk across the face after (side 0) or before (side 1) each tet.
        for (int side = 0; side < 2; ++side) {
          int ia = kTetEdge[k][0], ib = kTetEdge[k][1];
          std::uint32_t cur = std::uint32_t(t);
          for (;;) {
            const int exit = side == 0 ? kRing.c[ia][ib] : kRing.d[ia][ib];
            const std::uint32_t code = m.tet_adj_[4 * cur + exit];
            if (code == kNoNeighbour) break;
            cur = code >> 2;
            if (cur == t) { side = 2; break; }  // closed ring: done both ways
            const auto& sv = m.tets_[cur];
            ia = sv[0] == a ? 0 : sv[1] == a ? 1 : sv[2] == a ? 2 : 3;
            ib = sv[0] == b ? 0 : sv[1] == b ? 1 : sv[2] == b ? 2 : 3;
            m.tet_edge_[6 * cur + kEdgeOf[ia][ib]] = e;
          }
        }
      }
    }
  }
  m.vertex_class_.assign(nv, ModelRef{});
  m.edge_class_.assign(m.edge_verts_.size(), ModelRef{});
  m.tri_class_.assign(m.tri_verts_.size(), ModelRef{});
  return m;
}

}  // namespace polydual
