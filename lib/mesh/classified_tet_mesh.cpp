#include "mesh/classified_tet_mesh.h"

#include <algorithm>
#include <bit>
#include <numeric>
#include <stdexcept>

#include "core/error.h"

namespace polydual {

namespace {

using detail::kRing;
inline void ring_others(int ia, int ib, int& ic, int& id) {
  ic = kRing.c[ia][ib];
  id = kRing.d[ia][ib];
}

// A third tet on one triangle (the half-face `code` = 4t + i meets a face
// already paired), or two tets with the same four vertices. Out of line so the
// matching loop stays small.
[[noreturn, gnu::cold, gnu::noinline]] void throw_face_error(const ClassifiedTetMesh& m, std::uint32_t code,
                                                             std::uint32_t other_code, bool other_paired) {
  const std::uint32_t t = code / 4, t1 = other_code / 4;
  auto tet_place = [&](std::uint32_t x) { return "tet " + std::to_string(m.input_tet(TetId(x)) + 1); };
  if (!other_paired)
    throw InputError(m.source(), tet_place(std::max(t, t1)),
                     "duplicated tet (same four vertices as " + tet_place(std::min(t, t1)) + ")");
  const auto& tv = m.tet(TetId(t));
  std::uint32_t v[3] = {tv[kTetFace[code % 4][0]].idx, tv[kTetFace[code % 4][1]].idx, tv[kTetFace[code % 4][2]].idx};
  std::sort(v, v + 3);
  auto vnum = [&](std::uint32_t x) { return std::to_string(m.input_vertex(VertexId(x)) + 1); };
  const std::uint32_t t2 = m.tet_neighbor(TetId(t1), int(other_code % 4)).idx;
  throw InputError(m.source(), tet_place(std::min({t, t1, t2})),
                   "non-conformal mesh: triangle (" + vnum(v[0]) + ", " + vnum(v[1]) + ", " + vnum(v[2]) +
                       ") is shared by more than two tets (" + std::to_string(m.input_tet(TetId(t1)) + 1) + ", " +
                       std::to_string(m.input_tet(TetId(t2)) + 1) + ", " + std::to_string(m.input_tet(TetId(t)) + 1) + ")");
}

[[noreturn, gnu::cold, gnu::noinline]] void throw_overlap(const ClassifiedTetMesh& m, TetId t, TetId u) {
  throw InputError(m.source(), "tet " + std::to_string(std::min(m.input_tet(t), m.input_tet(u)) + 1),
                   "tets " + std::to_string(m.input_tet(t) + 1) + " and " + std::to_string(m.input_tet(u) + 1) +
                       " lie on the same side of their shared triangle: the mesh overlaps itself");
}

// kSideParity[o][i]: for a tet whose local indices by increasing vertex id are
// the 2-bit fields of o, the parity of the permutation (the other three local
// indices in increasing-id order, then i). orient(shared face in increasing
// ids, vertex i) is + for parity 0 in a positively oriented tet, so two tets
// on the two sides of a shared face have different parities.
struct SideParityTable {
  std::uint8_t bit[256][4] = {};
  constexpr SideParityTable() {
    for (int o = 0; o < 256; ++o)
      for (int i = 0; i < 4; ++i) {
        int perm[4] = {0, 0, 0, 0}, n = 0;
        for (int r = 0; r < 4; ++r)
          if (((o >> (2 * r)) & 3) != i) perm[n < 3 ? n++ : 3] = (o >> (2 * r)) & 3;
        perm[3] = i;
        int inv = 0;
        for (int x = 0; x < 4; ++x)
          for (int y = x + 1; y < 4; ++y) inv += perm[x] > perm[y];
        bit[o][i] = std::uint8_t(inv & 1);
      }
  }
};
constexpr SideParityTable kSideParity;

}  // namespace

const ModelEntity* ModelTopology::find(int dim, std::int32_t tag) const {
  const auto& v = entities[dim];
  auto it = std::lower_bound(v.begin(), v.end(), tag,
                             [](const ModelEntity& e, std::int32_t t) { return e.tag < t; });
  return (it != v.end() && it->tag == tag) ? &*it : nullptr;
}

FaceKind face_kind(const ModelEntity& face) {
  if (face.regions.size() < 2) return FaceKind::External;
  return face.regions[0] == face.regions[1] ? FaceKind::Fracture : FaceKind::Interface;
}

FaceKind ModelTopology::face_kind(std::int32_t tag) const {
  const ModelEntity* e = find(2, tag);
  if (!e) throw std::out_of_range("ModelTopology::face_kind: no model face with tag " + std::to_string(tag));
  return polydual::face_kind(*e);
}

EdgeId ClassifiedTetMesh::find_edge(VertexId a, VertexId b) const {
  if (a == b) return EdgeId::invalid();
  for (TetId t : vertex_tets(a)) {
    const int ia = local_index(t, a), ib = local_index(t, b);
    if (ib >= 0) return tet_edge(t, detail::kEdgeOf[ia][ib]);
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

void ClassifiedTetMesh::edge_ring_from(EdgeId e, TetId start, std::vector<TetId>& tets, std::vector<TriId>& tris,
                                       bool& closed) const {
  // Walk forwards from the start tet, across the face after each tet
  // (a, b, id); a closed ring comes back to the start. An open ring hits the
  // boundary: then walk backwards from the start (across (a, b, ic)) and put
  // that part in front, so the ring starts at the boundary.
  const auto [a, b] = edge(e);
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

std::vector<TetId> ClassifiedTetMesh::other_chain_starts(EdgeId e, std::span<const TetId> first) const {
  // The tets around e are those of a's star that have b. Each one not yet in
  // a chain starts the walk of its own chain (open: no chain of a mesh whose
  // tets do not overlap is closed but the only one).
  const auto [a, b] = edge(e);
  std::vector<TetId> seen(first.begin(), first.end()), starts, tets;
  std::vector<TriId> tris;
  for (TetId t : vertex_tets(a)) {
    if (local_index(t, b) < 0 || std::find(seen.begin(), seen.end(), t) != seen.end()) continue;
    bool closed;
    edge_ring_from(e, t, tets, tris, closed);
    starts.push_back(t);
    seen.insert(seen.end(), tets.begin(), tets.end());
  }
  return starts;
}

double ClassifiedTetMesh::tet_volume(TetId t) const {
  const auto& v = tets_[t.idx];
  Vec3 a = points_[v[0].idx];
  return dot(points_[v[1].idx] - a, cross(points_[v[2].idx] - a, points_[v[3].idx] - a)) / 6.0;
}

// Tets bucketed by their smallest, second and third smallest vertex
// (counting sorts, tet order kept in each bucket). Every tet face has its
// smallest vertex in bucket 0 (three faces) or 1 (the face opposite the
// smallest vertex); every tet edge has its lower vertex in bucket 0 (three
// edges), 1 (two) or 2 (one). Faces and edges are then found one vertex at a
// time among a few tets.
struct TetMeshBuilder::LowVertexBuckets {
  std::vector<std::uint8_t> sorted;  // per tet: its local indices by increasing vertex id, 2 bits each
  std::array<std::vector<std::uint32_t>, 3> off, bucket;  // bucket r: CSR by vertex of tets
};

namespace {
// The face-matching table: at least 2^6 slots (no resizing for small stars),
// hashed by the multiplicative (Fibonacci) hash of the key: 2^64 / golden ratio.
constexpr int kMinTableBits = 6;
constexpr std::uint64_t kFibonacciHash = 0x9E3779B97F4A7C15ull;
// Edge ids of a vertex's neighbours are ranked by counting (n^2 compares, no
// data-dependent branches) up to this many neighbours; more (a fan) are sorted.
constexpr std::size_t kMaxCountedNeighbours = 64;
// The edge count from Euler's relation is exact for a ball; the slack covers
// a few handles or cavities before the array has to grow.
constexpr std::size_t kEdgeGuessSlack = 16;
}  // namespace

// Flattened: the phases below are written as functions but compiled into
// this one (fewer instructions than as calls, callgrind), as the kernels were
// tuned.
[[gnu::flatten]] ClassifiedTetMesh TetMeshBuilder::build_topology(std::string source, std::vector<Point3> points,
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
  // Local entities are coded as 4 * tet + face and 8 * tet + edge in 32 bits.
  if (nt >= (std::size_t(1) << 29))
    throw InputError(m.source_, "", "more than 2^29 tets (" + std::to_string(nt) + ") are not supported");
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
  build_vertex_stars(m);
  const LowVertexBuckets b = bucket_by_low_vertices(m);
  const std::size_t num_tris = match_faces(m, b);
  check_opposite_sides(m, b);
  number_triangles(m, num_tris);
  number_edges(m, b, num_tris);
  find_multi_chain_edges(m);
  m.vertex_class_.assign(nv, ModelRef{});
  m.edge_class_.assign(m.edge_code_.size(), ModelRef{});
  m.tri_face_.assign(m.tri_code_.size(), ClassifiedTetMesh::kNoFace);
  return m;
}

void TetMeshBuilder::build_vertex_stars(ClassifiedTetMesh& m) {
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
}

TetMeshBuilder::LowVertexBuckets TetMeshBuilder::bucket_by_low_vertices(const ClassifiedTetMesh& m) {
  const std::size_t nv = m.points_.size(), nt = m.tets_.size();
  LowVertexBuckets b;
  auto& sorted = b.sorted;
  auto& boff = b.off;
  auto& bucket = b.bucket;
  sorted.resize(nt);
  {
    for (int r = 0; r < 3; ++r) boff[r].assign(nv + 1, 0);
    for (std::size_t t = 0; t < nt; ++t) {
      // Sorting network on (vertex id, local index) pairs packed in 64 bits.
      const auto& tv = m.tets_[t];
      std::uint64_t k[4];
      for (int i = 0; i < 4; ++i) k[i] = std::uint64_t(tv[i].idx) << 2 | std::uint64_t(i);
      auto cswap = [&](int i, int j) {  // selects, not branches: the order is random
        const std::uint64_t x = k[i], y = k[j];
        const bool swap = y < x;
        k[i] = swap ? y : x;
        k[j] = swap ? x : y;
      };
      cswap(0, 1); cswap(2, 3); cswap(0, 2); cswap(1, 3); cswap(1, 2);
      sorted[t] = std::uint8_t((k[0] & 3) | (k[1] & 3) << 2 | (k[2] & 3) << 4 | (k[3] & 3) << 6);
      for (int r = 0; r < 3; ++r) ++boff[r][(k[r] >> 2) + 1];
    }
    std::array<std::vector<std::uint32_t>, 3> fill;
    for (int r = 0; r < 3; ++r) {
      std::partial_sum(boff[r].begin(), boff[r].end(), boff[r].begin());
      bucket[r].resize(nt);
      fill[r].assign(boff[r].begin(), boff[r].end() - 1);
    }
    for (std::size_t t = 0; t < nt; ++t)
      for (int r = 0; r < 3; ++r) bucket[r][fill[r][m.tets_[t][(sorted[t] >> (2 * r)) & 3].idx]++] = std::uint32_t(t);
  }
  return b;
}

std::size_t TetMeshBuilder::match_faces(ClassifiedTetMesh& m, const LowVertexBuckets& b) {
  const std::size_t nv = m.points_.size(), nt = m.tets_.size();
  constexpr std::uint32_t kNoNeighbour = ClassifiedTetMesh::kNoNeighbour;
  const auto& sorted = b.sorted;
  const auto& boff = b.off;
  const auto& bucket = b.bucket;
  // Face adjacency: for each vertex v, the faces whose smallest vertex is v
  // (buckets 0 and 1), matched on their two other vertices (mid, max) in a
  // small open-addressing table (slots stamped with v, so nothing is cleared
  // between vertices). The two other vertices come out ordered from sorted[t]:
  // no comparisons. Whether a face is the first or the second of its pair is a
  // coin toss to a branch predictor, so that decision is made with selects; the
  // only branches are the probe loop (one step unless slots collide) and the
  // never-taken error check. Two equal faces pair; a third is a non-conformity.
  // One spare adjacency entry takes the writes of unpaired faces.
  m.tet_adj_.assign(4 * nt + 1, kNoNeighbour);
  const std::uint32_t sink = std::uint32_t(4 * nt);
  std::size_t num_tris = 0;
  {
    struct Slot { std::uint64_t key; std::uint32_t code, tag; };  // tag = 2 * (v + 1) + paired
    std::vector<Slot> table;
    for (std::size_t v = 0; v < nv; ++v) {
      const std::size_t n_here = 3 * std::size_t(boff[0][v + 1] - boff[0][v]) + (boff[1][v + 1] - boff[1][v]);
      // At most a quarter full: a probe rarely goes past its first slot.
      const int bits = std::max(kMinTableBits, int(std::bit_width(4 * n_here - (n_here > 0))));
      if (table.size() < (std::size_t(1) << bits)) table.assign(std::size_t(1) << bits, Slot{0, 0, 0});
      const std::uint64_t mask = (std::uint64_t(1) << bits) - 1;
      const std::uint32_t stamp = 2 * (std::uint32_t(v) + 1);
      auto add_face = [&](std::uint32_t t, int i, std::uint32_t mid, std::uint32_t max) {
        const std::uint64_t key = std::uint64_t(mid) << 32 | max;
        std::uint64_t h = (key * kFibonacciHash) >> (64 - bits);
        // Go on while the slot holds another key of this vertex, with ONE
        // branch per probe: whether the slot is taken is the coin toss, so
        // both tests are folded into one integer (zero iff taken and different).
        while ((std::uint64_t((table[h].tag & ~1u) ^ stamp) | std::uint64_t(table[h].key == key)) == 0)
          h = (h + 1) & mask;
        Slot& sl = table[h];
        const std::uint32_t code = 4 * t + std::uint32_t(i);
        const bool found = (sl.tag & ~1u) == stamp;
        const std::uint32_t other = sl.code;
        // A third face, or a twin tet (same vertex opposite the shared face).
        // `other` is a valid code even in a stale slot, so the load is safe and
        // the test stays one branch.
        const std::uint32_t bad =
            std::uint32_t(found) & ((sl.tag & 1u) | std::uint32_t(m.tets_[other >> 2][other & 3] == m.tets_[t][i]));
        if (bad != 0) [[unlikely]]
          throw_face_error(m, code, other, (sl.tag & 1u) != 0);
        // Selects as masks (a ?: here may be compiled as a branch).
        const std::uint32_t keep = 0u - std::uint32_t(found);  // all ones iff found
        sl.key = key;
        sl.code = (other & keep) | (code & ~keep);
        sl.tag = stamp | std::uint32_t(found);
        m.tet_adj_[(other & keep) | (sink & ~keep)] = code;
        m.tet_adj_[(code & keep) | (sink & ~keep)] = other;
        num_tris += !found;
      };
      for (std::uint32_t k = boff[0][v]; k < boff[0][v + 1]; ++k) {
        const std::uint32_t t = bucket[0][k];
        const int o = sorted[t], s1 = (o >> 2) & 3, s2 = (o >> 4) & 3, s3 = (o >> 6) & 3;
        const auto& tv = m.tets_[t];
        const std::uint32_t v1 = tv[s1].idx, v2 = tv[s2].idx, v3 = tv[s3].idx;
        add_face(t, s1, v2, v3);
        add_face(t, s2, v1, v3);
        add_face(t, s3, v1, v2);
      }
      for (std::uint32_t k = boff[1][v]; k < boff[1][v + 1]; ++k) {
        const std::uint32_t t = bucket[1][k];
        const int o = sorted[t];
        add_face(t, o & 3, m.tets_[t][(o >> 4) & 3].idx, m.tets_[t][(o >> 6) & 3].idx);
      }
    }
  }
  m.tet_adj_.pop_back();
  return num_tris;
}

// Two positively oriented tets sharing a triangle must lie on its two sides
// (combinatorial, hence exact: the orientations were decided exactly before).
// Without it an overlapping mesh pairs its faces consistently enough to pass
// the conformity check and sends the walks around an edge into a cycle that
// never returns to its start. Branch-free over every face (each pair is seen
// twice; the table lookup is cheaper than a branch on the order of the two
// tets); the pair is looked for only when one is wrong.
void TetMeshBuilder::check_opposite_sides(const ClassifiedTetMesh& m, const LowVertexBuckets& b) {
  constexpr std::uint32_t kNo = ClassifiedTetMesh::kNoNeighbour;
  const std::size_t nt = m.tets_.size();
  const auto& adj = m.tet_adj_;
  const auto& sorted = b.sorted;
  std::uint32_t bad = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint8_t* mine = kSideParity.bit[sorted[t]];
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t c = adj[4 * t + std::size_t(i)], has = c != kNo;
      const std::uint32_t u = has ? c >> 2 : std::uint32_t(t);  // a safe index on the boundary
      bad |= has & std::uint32_t(mine[i] == kSideParity.bit[sorted[u]][c & 3]);
    }
  }
  if (bad == 0) [[likely]]
    return;
  for (std::size_t t = 0; t < nt; ++t)
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t c = adj[4 * t + std::size_t(i)];
      if (c != kNo && kSideParity.bit[sorted[t]][i] == kSideParity.bit[sorted[c >> 2]][c & 3])
        throw_overlap(m, TetId(t), TetId(c >> 2));
    }
}

void TetMeshBuilder::number_triangles(ClassifiedTetMesh& m, std::size_t num_tris) {
  const std::size_t nt = m.tets_.size();
  // Triangles, numbered in the order (tet, local face) of their first tet: a
  // face is new unless its neighbour comes earlier (branch-free). The face
  // -> triangle map is not stored: one bit per local face marks the first
  // ones, and a triangle id is the rank of its first face (tet_triangle()).
  m.tri_code_.resize(num_tris + 1);
  m.tri_first_bits_.assign((4 * nt + 63) / 64, 0);
  m.tri_first_rank_.resize(m.tri_first_bits_.size());
  {
    std::uint32_t next = 0;
    for (std::size_t w = 0; w < m.tri_first_bits_.size(); ++w) {
      m.tri_first_rank_[w] = next;
      std::uint64_t bits = 0;
      const std::uint32_t end = std::uint32_t(std::min<std::size_t>(4 * nt, 64 * (w + 1)));
      for (std::uint32_t c = std::uint32_t(64 * w); c < end; ++c) {
        const bool fresh = m.tet_adj_[c] > c;  // kNoNeighbour is above every code
        m.tri_code_[next] = c;
        next += fresh;
        bits |= std::uint64_t(fresh) << (c & 63);
      }
      m.tri_first_bits_[w] = bits;
    }
  }
  m.tri_code_.pop_back();
}

void TetMeshBuilder::number_edges(ClassifiedTetMesh& m, const LowVertexBuckets& b, std::size_t num_tris) {
  const std::size_t nv = m.points_.size(), nt = m.tets_.size();
  const auto& sorted = b.sorted;
  const auto& boff = b.off;
  const auto& bucket = b.bucket;
  // Edges, numbered by (lower vertex v, higher vertex w): for each v, the tet
  // edges whose lower vertex is v (buckets 0..2) are gathered once; their
  // distinct w (a marker per vertex) get consecutive ids in increasing w, each
  // id from its rank among them (counted, not sorted: no data-dependent
  // branches). An edge's stored tet is the tet of its first record.
  {
    std::vector<std::uint32_t> mark(nv, std::uint32_t(-1)), slot(nv, 0);
    struct Rec { std::uint32_t w, code; };  // code = 8 * tet + local edge
    std::vector<Rec> recs, nbs;
    m.tet_edge_.resize(6 * nt);
    // Euler's relation for a ball: E = V + T + (boundary triangles)/2 - 1.
    const std::size_t ne_guess = nv + nt + (2 * num_tris - 4 * nt) / 2 + kEdgeGuessSlack;
    m.edge_code_.reserve(ne_guess);
    for (std::size_t v = 0; v < nv; ++v) {
      const std::uint32_t vv = std::uint32_t(v);
      const std::size_t most = 3 * std::size_t(boff[0][v + 1] - boff[0][v]) +
                               2 * std::size_t(boff[1][v + 1] - boff[1][v]) + (boff[2][v + 1] - boff[2][v]);
      if (recs.size() < most) {
        recs.resize(most);
        nbs.resize(most + 1);
      }
      std::size_t n_recs = 0, n_nbs = 0;
      for (int r = 0; r < 3; ++r)
        for (std::uint32_t k = boff[r][v]; k < boff[r][v + 1]; ++k) {
          const std::uint32_t t = bucket[r][k];
          const int o = sorted[t], iv = (o >> (2 * r)) & 3;
          for (int q = r + 1; q < 4; ++q) {
            const int iw = (o >> (2 * q)) & 3;
            const std::uint32_t w = m.tets_[t][iw].idx, code = 8 * t + std::uint32_t(detail::kEdgeOf[iv][iw]);
            recs[n_recs++] = {w, code};
            nbs[n_nbs] = {w, code};  // kept only if w is new
            n_nbs += mark[w] != vv;
            mark[w] = vv;
          }
        }
      const std::uint32_t base = std::uint32_t(m.edge_code_.size());
      m.edge_code_.resize(base + n_nbs);
      // Counting is quadratic: a vertex with very many neighbours (a fan) sorts.
      if (n_nbs > kMaxCountedNeighbours) std::sort(nbs.begin(), nbs.begin() + std::ptrdiff_t(n_nbs), [](Rec x, Rec y) { return x.w < y.w; });
      for (std::size_t i = 0; i < n_nbs; ++i) {
        if (n_nbs > kMaxCountedNeighbours) {
          m.edge_code_[base + i] = nbs[i].code;
          slot[nbs[i].w] = base + std::uint32_t(i);
          continue;
        }
        std::uint32_t rank = 0;
        for (std::size_t j = 0; j < n_nbs; ++j) rank += nbs[j].w < nbs[i].w;
        m.edge_code_[base + rank] = nbs[i].code;
        slot[nbs[i].w] = base + rank;
      }
      for (std::size_t i = 0; i < n_recs; ++i)
        m.tet_edge_[6 * (recs[i].code >> 3) + (recs[i].code & 7)] = EdgeId(slot[recs[i].w]);
    }
  }
}

// An open chain of an edge begins and ends on a boundary triangle (a tet face
// without a neighbour), and a closed chain has none; so an edge has several
// chains iff more than two boundary triangles meet at it (proofs/
// edge_chains.md E1). A tight pass gathers the tets with a boundary face
// (kNoNeighbour is the only neighbour code with bit 31 set: codes stay below
// 4 * 2^29, so a tet's four sign bits list its boundary faces), then a byte
// per edge counts the boundary triangles at it (saturating). 22 instructions
// per tet on twomat 100k (callgrind; build_topology takes ~1050). Not inlined
// into build_topology: a phase of its own in profiles.
[[gnu::noinline]] void TetMeshBuilder::find_multi_chain_edges(ClassifiedTetMesh& m) {
  const std::size_t nt = m.tets_.size();
  const std::uint32_t* adj = m.tet_adj_.data();
  auto boundary_faces = [&](std::size_t t) {
#if defined(__SSE2__)
    return unsigned(_mm_movemask_ps(_mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(adj + 4 * t)))));
#else
    return unsigned(adj[4 * t] >> 31 | (adj[4 * t + 1] >> 31) << 1 | (adj[4 * t + 2] >> 31) << 2 |
                    (adj[4 * t + 3] >> 31) << 3);
#endif
  };
  // Tets with a boundary face, gathered without branches (written always,
  // counted when the tet has one); at most one per boundary face.
  const std::size_t num_boundary = 2 * m.tri_code_.size() - 4 * nt;  // 4 nt = 2 interior + boundary
  std::vector<std::uint32_t> tets(num_boundary + 1);
  std::size_t n = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    tets[n] = std::uint32_t(t);
    n += boundary_faces(t) != 0;
  }
  // The three local edges of local face i (the edges without local vertex i).
  static constexpr int kFaceEdges[4][3] = {{3, 4, 5}, {1, 2, 5}, {0, 2, 4}, {0, 1, 3}};
  std::vector<std::uint8_t> count(m.edge_code_.size(), 0);
  std::vector<std::uint32_t> touched;  // edges with a boundary triangle (repeats allowed)
  touched.reserve(3 * num_boundary);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t t = tets[k];
    for (unsigned faces = boundary_faces(t); faces != 0; faces &= faces - 1)
      for (int q : kFaceEdges[std::countr_zero(faces)]) {
        const std::uint32_t e = m.tet_edge_[6 * t + std::size_t(q)].idx;
        count[e] = std::uint8_t(count[e] + (count[e] < 255));
        touched.push_back(e);
      }
  }
  m.multi_chain_edges_.clear();
  for (std::uint32_t e : touched)
    if (count[e] > 2) {
      m.multi_chain_edges_.push_back(EdgeId(e));
      count[e] = 0;  // listed once
    }
  std::sort(m.multi_chain_edges_.begin(), m.multi_chain_edges_.end(),
            [](EdgeId x, EdgeId y) { return x.idx < y.idx; });
}

ClassifiedTetMesh ClassifiedTetMesh::with_points(std::vector<Point3> points) const {
  if (points.size() != num_vertices())
    throw UsageError("with_points: " + std::to_string(points.size()) + " points for a mesh of " +
                     std::to_string(num_vertices()) + " vertices");
  ClassifiedTetMesh out = *this;
  out.points_ = std::move(points);
  return out;
}

std::vector<VertexId> internal_of_input(const ClassifiedTetMesh& m) {
  std::uint32_t n = 0;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) n = std::max(n, m.input_vertex(VertexId(v)) + 1);
  std::vector<VertexId> out(n, VertexId::invalid());
  for (std::size_t v = 0; v < m.num_vertices(); ++v) out[m.input_vertex(VertexId(v))] = VertexId(v);
  return out;
}

}  // namespace polydual
