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

std::string tet_place(std::size_t t) { return "tet " + std::to_string(t + 1); }
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
  const VertexId a = edge_verts_[e.idx][0], b = edge_verts_[e.idx][1];
  const TetId start = edge_tet_[e.idx];
  // Walk backwards (across the face opposite `id`, which holds a, b, ic) to the
  // first tet of an open ring.
  TetId first = start;
  bool is_closed = false;
  for (;;) {
    int ic, id;
    ring_others(local_index(first, a), local_index(first, b), ic, id);
    TetId prev = tet_neighbor(first, id);
    if (!prev.valid()) break;
    if (prev == start) { is_closed = true; break; }
    first = prev;
  }
  std::vector<TetId> ring;
  TetId t = first;
  for (;;) {
    ring.push_back(t);
    int ic, id;
    ring_others(local_index(t, a), local_index(t, b), ic, id);
    TetId next = tet_neighbor(t, ic);  // across (a, b, id)
    if (!next.valid() || next == first) break;
    t = next;
  }
  if (closed) *closed = is_closed;
  return ring;
}

void ClassifiedTetMesh::edge_ring(EdgeId e, std::vector<TetId>& tets, std::vector<TriId>& tris,
                                  bool& closed) const {
  tets = edge_ring(e, &closed);
  tris.clear();
  const VertexId a = edge_verts_[e.idx][0], b = edge_verts_[e.idx][1];
  for (std::size_t k = 0; k < tets.size(); ++k) {
    int ic, id;
    ring_others(local_index(tets[k], a), local_index(tets[k], b), ic, id);
    if (k == 0) tris.push_back(tet_triangle(tets[k], id));  // face (a, b, ic): before
    tris.push_back(tet_triangle(tets[k], ic));              // face (a, b, id): after
  }
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
                                                 std::vector<std::int32_t> regions) {
  ClassifiedTetMesh m;
  m.source_ = std::move(source);
  m.points_ = std::move(points);
  m.tets_ = std::move(tets);
  m.tet_region_ = std::move(regions);
  const std::size_t nv = m.points_.size(), nt = m.tets_.size();

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
                             "duplicated tet (same four vertices as tet " + std::to_string(t + 1) + ")");
          if (n > 2)
            throw InputError(m.source_, tet_place(t),
                             "non-conformal mesh: triangle (" + std::to_string(v + 1) + ", " +
                                 std::to_string(it->mid + 1) + ", " + std::to_string(it->max + 1) +
                                 ") is shared by more than two tets (" + std::to_string(t + 1) + ", " +
                                 std::to_string(s2 + 1) + ", " + std::to_string((it + 2)->code / 4 + 1) + ")");
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
  // Edges: numbered by (lower vertex, higher vertex); per vertex a sorted list of
  // higher neighbours for the tet -> edge lookup.
  std::vector<std::uint32_t> nb_off(nv + 1, 0);
  std::vector<std::uint32_t> nb;  // higher neighbours, CSR
  {
    std::vector<std::uint32_t> stamp(nv, std::uint32_t(-1));
    std::vector<std::uint32_t> tmp;
    for (std::size_t a = 0; a < nv; ++a) {
      tmp.clear();
      for (TetId t : m.vertex_tets(VertexId(a)))
        for (VertexId b : m.tets_[t.idx])
          if (b.idx > a && stamp[b.idx] != a) { stamp[b.idx] = std::uint32_t(a); tmp.push_back(b.idx); }
      std::sort(tmp.begin(), tmp.end());
      nb.insert(nb.end(), tmp.begin(), tmp.end());
      nb_off[a + 1] = std::uint32_t(nb.size());
    }
  }
  m.edge_verts_.resize(nb.size());
  m.edge_tet_.assign(nb.size(), TetId::invalid());
  for (std::size_t a = 0; a < nv; ++a)
    for (std::uint32_t k = nb_off[a]; k < nb_off[a + 1]; ++k)
      m.edge_verts_[k] = {VertexId(a), VertexId(nb[k])};
  m.tet_edge_.resize(6 * nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tv = m.tets_[t];
    for (int k = 0; k < 6; ++k) {
      std::uint32_t a = tv[kTetEdge[k][0]].idx, b = tv[kTetEdge[k][1]].idx;
      if (a > b) std::swap(a, b);
      auto it = std::lower_bound(nb.begin() + nb_off[a], nb.begin() + nb_off[a + 1], b);
      EdgeId e(static_cast<std::uint32_t>(it - nb.begin()));
      m.tet_edge_[6 * t + k] = e;
      if (!m.edge_tet_[e.idx].valid()) m.edge_tet_[e.idx] = TetId(t);
    }
  }
  m.vertex_class_.assign(nv, ModelRef{});
  m.edge_class_.assign(m.edge_verts_.size(), ModelRef{});
  m.tri_class_.assign(m.tri_verts_.size(), ModelRef{});
  return m;
}

}  // namespace polydual
