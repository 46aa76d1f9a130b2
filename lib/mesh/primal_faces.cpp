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

}  // namespace

void PrimalMeshBuilder::match_faces(PrimalMesh& m, const CellSoup& soup) {
  // The cell-local faces in (sorted key, cell) order: their keys in cell
  // order, then for each vertex a the faces of a's star whose smallest
  // vertex is a, sorted by the rest of the key and the cell (a walk of the
  // stars, as number_edges).
  std::vector<std::array<std::uint32_t, 4>> keys(m.cell_face_off_.back());
  for (std::size_t c = 0; c < m.num_cells(); ++c) {
    const CellDescriptor& d = descriptor(m.cell_type_[c]);
    const auto cv = m.cell_vertices(PrimalCellId(c));
    for (int i = 0; i < d.num_faces; ++i) {
      auto& key = keys[m.cell_face_off_[c] + std::uint64_t(i)];
      key = {kPad, kPad, kPad, kPad};
      for (int k = 0; k < d.face_size[i]; ++k) key[k] = cv[d.faces[i][k]].idx;
      std::sort(key.begin(), key.end());
    }
  }
  std::vector<LocalFace> all;
  all.reserve(keys.size());
  for (std::size_t a = 0; a < m.num_vertices(); ++a) {
    const std::size_t first = all.size();
    for (PrimalCellId c : m.vertex_cells(VertexId(a))) {
      const std::uint64_t off = m.cell_face_off_[c.idx];
      for (std::uint64_t i = 0; i < m.cell_face_off_[c.idx + 1] - off; ++i)
        if (keys[off + i][0] == a) all.push_back({keys[off + i], c.idx, std::uint8_t(i)});
    }
    std::sort(all.begin() + std::ptrdiff_t(first), all.end(), [](const LocalFace& x, const LocalFace& y) {
      const std::uint64_t x12 = std::uint64_t(x.key[1]) << 32 | x.key[2], y12 = std::uint64_t(y.key[1]) << 32 | y.key[2];
      if (x12 != y12) return x12 < y12;
      return (std::uint64_t(x.key[3]) << 32 | x.cell) < (std::uint64_t(y.key[3]) << 32 | y.cell);
    });
  }
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

// Edges numbered by (lower vertex a, higher vertex b), their cells in
// increasing order: for each a, the cell-local edges (a, b > a) of a's star
// are gathered and sorted by (b, cell). The star walk reads cells near each
// other; one sort of all cell-local edges (a hexahedral mesh has 12 per
// cell) scattered them across memory at twice the cost.
void PrimalMeshBuilder::number_edges(PrimalMesh& m) {
  struct LocalEdge {
    std::uint64_t key;  // b << 32 | cell
    std::uint8_t local;  // 2 * local edge + (whether it runs from b to a)
  };
  std::vector<LocalEdge> recs;
  const std::size_t nv = m.num_vertices();
  m.cell_edge_.resize(m.cell_edge_off_.back());
  m.ecell_.resize(m.cell_edge_off_.back());
  m.ecell_local_.resize(m.cell_edge_off_.back());
  m.ecell_off_.assign(1, 0);
  m.vedge_off_.assign(nv + 1, 0);
  std::size_t at = 0;
  for (std::size_t a = 0; a < nv; ++a) {
    recs.clear();
    for (PrimalCellId c : m.vertex_cells(VertexId(a))) {
      const CellDescriptor& d = m.cell_descriptor(c);
      const auto cv = m.cell_vertices(c);
      for (int k = 0; k < d.num_edges; ++k) {
        const std::uint32_t x = cv[d.edges[k][0]].idx, y = cv[d.edges[k][1]].idx;
        if (std::min(x, y) == a) recs.push_back({std::uint64_t(std::max(x, y)) << 32 | c.idx, std::uint8_t(2 * k + (x != a))});
      }
    }
    std::sort(recs.begin(), recs.end(), [](const LocalEdge& x, const LocalEdge& y) { return x.key < y.key; });
    for (std::size_t i = 0; i < recs.size(); ++i) {
      const std::uint32_t b = std::uint32_t(recs[i].key >> 32), c = std::uint32_t(recs[i].key);
      if (i == 0 || b != std::uint32_t(recs[i - 1].key >> 32)) {
        if (!m.edge_vertex_.empty()) m.ecell_off_.push_back(at);
        m.edge_vertex_.push_back({VertexId(std::uint32_t(a)), VertexId(b)});
      }
      m.cell_edge_[m.cell_edge_off_[c] + recs[i].local / 2] = EdgeId(m.edge_vertex_.size() - 1);
      m.ecell_local_[at] = recs[i].local;
      m.ecell_[at++] = PrimalCellId(c);
    }
    m.vedge_off_[a + 1] = m.edge_vertex_.size();
  }
  m.ecell_off_.push_back(at);
}

}  // namespace polydual
