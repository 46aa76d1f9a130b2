// PrimalMeshBuilder: faces shared whole by at most two cells with opposite
// orientations, no quadrangle against two triangles, and the edges.
#include <algorithm>
#include <unordered_map>

#include "core/error.h"
#include "mesh/cell_soup.h"
#include "mesh/primal_mesh.h"

namespace polydual {
namespace {

constexpr std::uint32_t kPad = 0xffffffffu;

std::string vertex_list(std::span<const VertexId> v) {
  std::string s = "(";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += ' ';
    s += std::to_string(v[i].idx + 1);
  }
  return s + ")";
}

// Whether loop y is loop x reversed (+1), x itself (-1) up to rotation, or
// neither (0: a quadrangle's vertices in another order).
int opposite_loops(std::span<const VertexId> x, std::span<const VertexId> y) {
  const std::size_t n = x.size();
  if (y.size() != n) return 0;
  const std::size_t r = std::size_t(std::find(y.begin(), y.end(), x[0]) - y.begin());
  if (r == n) return 0;
  bool rev = true, same = true;
  for (std::size_t k = 0; k < n; ++k) {
    rev = rev && y[(r + n - k) % n] == x[k];
    same = same && y[(r + k) % n] == x[k];
  }
  return rev ? 1 : same ? -1 : 0;
}

// items ordered by first(item), a vertex index below num_vertices, then by
// `less` among the items of one vertex: a counting sort on the vertex, then
// a sort of each vertex's few items. The same order as one std::sort by
// (first, less) when that is a total order on the items, at a fraction of its
// cost: a hexahedral mesh has some 1.2 million cell-local edges and faces.
template <class T, class First, class Less>
void sort_by_vertex(std::vector<T>& items, std::size_t num_vertices, First first, Less less) {
  std::vector<std::uint64_t> off(num_vertices + 1, 0);
  for (const T& x : items) ++off[first(x) + 1];
  for (std::size_t v = 0; v < num_vertices; ++v) off[v + 1] += off[v];
  std::vector<T> sorted(items.size());
  std::vector<std::uint64_t> at(off.begin(), off.end() - 1);
  for (const T& x : items) sorted[at[first(x)]++] = x;
  for (std::size_t v = 0; v < num_vertices; ++v)
    if (off[v + 1] - off[v] > 1) std::sort(sorted.begin() + off[v], sorted.begin() + off[v + 1], less);
  items = std::move(sorted);
}

}  // namespace

void PrimalMeshBuilder::match_faces(PrimalMesh& m, const CellSoup& soup) {
  std::vector<LocalFace> all;
  all.reserve(m.cell_face_off_.back());
  for (std::size_t c = 0; c < m.num_cells(); ++c) {
    const CellDescriptor& d = descriptor(m.cell_type_[c]);
    const auto cv = m.cell_vertices(PrimalCellId(c));
    for (int i = 0; i < d.num_faces; ++i) {
      LocalFace f{{kPad, kPad, kPad, kPad}, std::uint32_t(c), std::uint8_t(i)};
      for (int k = 0; k < d.face_size[i]; ++k) f.key[k] = cv[d.faces[i][k]].idx;
      std::sort(f.key.begin(), f.key.end());
      all.push_back(f);
    }
  }
  // Within a bucket key[0] is the same: the rest of LocalFace's order.
  sort_by_vertex(all, m.num_vertices(), [](const LocalFace& f) { return f.key[0]; },
                 [](const LocalFace& x, const LocalFace& y) {
                   const std::uint64_t x12 = std::uint64_t(x.key[1]) << 32 | x.key[2],
                                       y12 = std::uint64_t(y.key[1]) << 32 | y.key[2];
                   if (x12 != y12) return x12 < y12;
                   return (std::uint64_t(x.key[3]) << 32 | x.cell) < (std::uint64_t(y.key[3]) << 32 | y.cell);
                 });
  m.cell_face_.resize(all.size());
  m.cell_face_side_.resize(all.size());
  m.cell_nbr_.resize(all.size());
  m.face_off_.assign(1, 0);
  auto local_loop = [&](const LocalFace& f) {
    const CellDescriptor& d = descriptor(m.cell_type_[f.cell]);
    const auto cv = m.cell_vertices(PrimalCellId(f.cell));
    std::array<VertexId, 4> loop{};
    for (int k = 0; k < d.face_size[f.local]; ++k) loop[k] = cv[d.faces[f.local][k]];
    return std::pair{loop, std::size_t(d.face_size[f.local])};
  };
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i + 1;
    while (j < all.size() && all[j].key == all[i].key) ++j;
    const PrimalFaceId f(m.face_cell_.size());
    const auto [loop, n] = local_loop(all[i]);
    const std::span<const VertexId> owner(loop.data(), n);
    if (j - i > 2)
      throw InputError(soup.source, cell_place(soup, all[i].cell),
                       "face " + vertex_list(owner) + " is shared by " + std::to_string(j - i) + " cells (" +
                           cell_place(soup, all[i].cell) + ", " + cell_place(soup, all[i + 1].cell) + ", " +
                           cell_place(soup, all[i + 2].cell) + (j - i > 3 ? ", ..." : "") + "); at most two may share one");
    if (j - i == 2) {
      const auto [other, n2] = local_loop(all[i + 1]);
      const int o = opposite_loops(owner, std::span<const VertexId>(other.data(), n2));
      if (o != 1)
        throw InputError(soup.source, cell_place(soup, all[i].cell),
                         cell_place(soup, all[i].cell) + " and " + cell_place(soup, all[i + 1].cell) + " share face " +
                             vertex_list(owner) +
                             (o == -1 ? " with the same orientation (the cells overlap)"
                                      : " with its vertices in different orders (a non-conformal quadrangle)"));
    }
    m.face_vtx_.insert(m.face_vtx_.end(), owner.begin(), owner.end());
    m.face_off_.push_back(m.face_vtx_.size());
    m.face_cell_.push_back({PrimalCellId(all[i].cell), j - i == 2 ? PrimalCellId(all[i + 1].cell) : PrimalCellId()});
    for (std::size_t k = i; k < j; ++k) {
      const std::uint64_t at = m.cell_face_off_[all[k].cell] + all[k].local;
      m.cell_face_[at] = f;
      m.cell_face_side_[at] = std::uint8_t(k - i);
      m.cell_nbr_[at] = j - i == 2 ? PrimalCellId(all[i + 1 - (k - i)].cell) : PrimalCellId();
    }
    i = j;
  }
}

// A boundary quadrangle three of whose vertices make a boundary triangle of
// another cell: the quad meets two triangles across its diagonal (or a
// triangle and a gap), which Algorithm 1 cannot dualise.
void PrimalMeshBuilder::check_hanging_quads(const PrimalMesh& m, const CellSoup& soup) {
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> boundary_tris;  // hash of key -> faces
  auto hash = [](std::array<std::uint32_t, 3> k) {
    return (std::uint64_t(k[0]) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(k[1]) * 0xC2B2AE3D27D4EB4Full) ^ k[2];
  };
  auto key_of = [](std::span<const VertexId> v, std::size_t skip) {
    std::array<std::uint32_t, 3> k{};
    for (std::size_t i = 0, n = 0; i < v.size(); ++i)
      if (i != skip) k[n++] = v[i].idx;
    std::sort(k.begin(), k.end());
    return k;
  };
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (!m.face_cell_[f][1].valid() && m.face_vertices(PrimalFaceId(f)).size() == 3)
      boundary_tris[hash(key_of(m.face_vertices(PrimalFaceId(f)), 3))].push_back(std::uint32_t(f));
  if (boundary_tris.empty()) return;
  for (std::size_t q = 0; q < m.num_faces(); ++q) {
    const auto qv = m.face_vertices(PrimalFaceId(q));
    if (m.face_cell_[q][1].valid() || qv.size() != 4) continue;
    for (std::size_t skip = 0; skip < 4; ++skip) {
      const auto k = key_of(qv, skip);
      const auto it = boundary_tris.find(hash(k));
      if (it == boundary_tris.end()) continue;
      for (std::uint32_t t : it->second) {
        if (key_of(m.face_vertices(PrimalFaceId(t)), 3) != k) continue;
        const std::size_t qc = m.face_cell_[q][0].idx, tc = m.face_cell_[t][0].idx;
        throw InputError(soup.source, cell_place(soup, qc),
                         "non-conformal mesh: quadrangle face " + vertex_list(qv) + " of " + cell_place(soup, qc) +
                             " meets triangle face " + vertex_list(m.face_vertices(PrimalFaceId(t))) + " of " +
                             cell_place(soup, tc) + "; a quadrangle must be shared whole (split it with a pyramid)");
      }
    }
  }
}

void PrimalMeshBuilder::number_edges(PrimalMesh& m) {
  struct LocalEdge {
    std::array<VertexId, 2> key;
    std::uint32_t cell;
    std::uint8_t local;
  };
  std::vector<LocalEdge> all;
  all.reserve(m.cell_edge_off_.back());
  for (std::size_t c = 0; c < m.num_cells(); ++c) {
    const CellDescriptor& d = descriptor(m.cell_type_[c]);
    const auto cv = m.cell_vertices(PrimalCellId(c));
    for (int k = 0; k < d.num_edges; ++k) {
      VertexId a = cv[d.edges[k][0]], b = cv[d.edges[k][1]];
      if (b < a) std::swap(a, b);
      all.push_back({{a, b}, std::uint32_t(c), std::uint8_t(k)});
    }
  }
  // Within a bucket key[0] is the same: by (key[1], cell), as one sort by (key, cell).
  sort_by_vertex(all, m.num_vertices(), [](const LocalEdge& e) { return e.key[0].idx; },
                 [](const LocalEdge& x, const LocalEdge& y) {
                   return (std::uint64_t(x.key[1].idx) << 32 | x.cell) < (std::uint64_t(y.key[1].idx) << 32 | y.cell);
                 });
  m.cell_edge_.resize(all.size());
  m.ecell_.resize(all.size());
  m.ecell_off_.assign(1, 0);
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i == 0 || all[i].key != all[i - 1].key) {
      if (i) m.ecell_off_.push_back(i);
      m.edge_vertex_.push_back(all[i].key);
    }
    m.cell_edge_[m.cell_edge_off_[all[i].cell] + all[i].local] = EdgeId(m.edge_vertex_.size() - 1);
    m.ecell_[i] = PrimalCellId(all[i].cell);
  }
  m.ecell_off_.push_back(all.size());
  m.vedge_off_.assign(m.num_vertices() + 1, 0);
  for (const auto& e : m.edge_vertex_) ++m.vedge_off_[e[0].idx + 1];
  for (std::size_t v = 0; v < m.num_vertices(); ++v) m.vedge_off_[v + 1] += m.vedge_off_[v];
}

}  // namespace polydual
