// PrimalMesh queries (the edge chains) and PrimalMeshBuilder's connectivity:
// vertex stars, face matching with the conformity checks, edge numbering.
// Classification is completed in primal_classification.cpp.
#include "mesh/primal_mesh.h"

#include <algorithm>
#include <unordered_map>

#include "core/error.h"
#include "mesh/cell_soup.h"

namespace polydual {

std::array<int, 2> PrimalMesh::faces_at_edge(PrimalCellId c, int ia, int ib) const {
  const CellDescriptor& d = cell_descriptor(c);
  std::array<int, 2> out{-1, -1};
  for (int i = 0; i < d.num_faces; ++i) {
    const int n = d.face_size[i];
    for (int k = 0; k < n; ++k) {
      const int p = d.faces[i][k], q = d.faces[i][(k + 1) % n];
      if (p == ia && q == ib) out[0] = i;  // leads out: right-handed about ia -> ib
      if (p == ib && q == ia) out[1] = i;  // leads in
    }
  }
  return out;
}

// Walks back from `start` to the chain's first cell (or round to start), then
// forward collecting cells and the faces between them.
EdgeChain PrimalMesh::chain_from(PrimalCellId start, VertexId a, VertexId b) const {
  auto lead = [&](PrimalCellId c, int which) {
    const auto [ia, ib] = local_indices(c, a, b);
    const int i = faces_at_edge(c, ia, ib)[which];
    return std::pair{cell_face(c, i), cell_neighbor(c, i)};
  };
  PrimalCellId first = start;
  for (;;) {
    const PrimalCellId prev = lead(first, 1).second;
    if (!prev.valid() || prev == start) break;
    first = prev;
  }
  EdgeChain chain;
  chain.faces.push_back(lead(first, 1).first);
  PrimalCellId c = first;
  do {
    chain.cells.push_back(c);
    const auto [f, next] = lead(c, 0);
    chain.faces.push_back(f);
    c = next;
  } while (c.valid() && c != first);
  chain.closed = c == first;
  return chain;
}

std::vector<EdgeChain> PrimalMesh::edge_chains(EdgeId e) const {
  std::vector<EdgeChain> out;
  if (dim_ != 3) return out;
  const auto [a, b] = edge(e);
  const auto around = edge_cells(e);
  std::vector<char> placed(around.size(), 0);
  for (std::size_t i = 0; i < around.size(); ++i) {
    if (placed[i]) continue;
    out.push_back(chain_from(around[i], a, b));
    for (PrimalCellId c : out.back().cells)
      placed[std::lower_bound(around.begin(), around.end(), c) - around.begin()] = 1;
  }
  return out;
}

EdgeId PrimalMesh::find_edge(VertexId a, VertexId b) const {
  if (b < a) std::swap(a, b);
  if (a.idx + 1 >= vedge_off_.size()) return EdgeId::invalid();
  const auto first = edge_vertex_.begin() + std::ptrdiff_t(vedge_off_[a.idx]);
  const auto last = edge_vertex_.begin() + std::ptrdiff_t(vedge_off_[a.idx + 1]);
  for (auto it = first; it != last; ++it)  // a vertex's few edges, increasing b
    if ((*it)[1] == b) return EdgeId(std::size_t(it - edge_vertex_.begin()));
  return EdgeId::invalid();
}

std::vector<VertexId> internal_of_input(const PrimalMesh& m) {
  GlobalId n = 0;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) n = std::max(n, m.input_vertex(VertexId(v)) + 1);
  std::vector<VertexId> out(n, VertexId::invalid());
  for (std::size_t v = 0; v < m.num_vertices(); ++v) out[m.input_vertex(VertexId(v))] = VertexId(std::uint32_t(v));
  return out;
}

bool any_marked(std::span<const VertexId> vs, const std::vector<char>& marked) {
  if (marked.empty()) return false;
  for (VertexId v : vs)
    if (marked[v.idx]) return true;
  return false;
}

Point3 vertex_mean(const PrimalMesh& m, std::span<const VertexId> vs) {
  Point3 p{0, 0, 0};
  for (VertexId v : vs) p = p + m.point(v);
  return p * (1.0 / double(vs.size()));
}

// ---------------------------------------------------------------- builder

PrimalMesh PrimalMeshBuilder::build(const CellSoup& soup) {
  PrimalMesh m;
  copy_cells(m, soup);
  build_vertex_stars(m);
  if (m.dim_ == 3) {
    match_faces(m, soup);
    check_hanging_quads(m, soup);
  }
  number_edges(m);
  classify_faces(m, soup);
  classify_edges(m, soup);
  classify_vertices(m, soup);
  return m;
}

void PrimalMeshBuilder::copy_cells(PrimalMesh& m, const CellSoup& soup) {
  m.source_ = soup.source;
  m.points_ = soup.points;
  m.cell_type_ = soup.cell_type;
  m.cell_region_ = soup.cell_region;
  m.cell_off_ = soup.cell_offset;
  m.cell_vtx_.reserve(soup.cell_vertex.size());
  for (std::uint32_t v : soup.cell_vertex) m.cell_vtx_.push_back(VertexId(v));
  m.dim_ = 2;
  for (CellType t : soup.cell_type)
    if (descriptor(t).dim == 3) m.dim_ = 3;
  for (std::size_t c = 0; c < soup.num_cells(); ++c) {
    const CellDescriptor& d = descriptor(soup.cell_type[c]);
    if (d.dim != m.dim_)
      throw InputError(soup.source, cell_place(soup, c),
                       "a " + std::string(d.name) + " among volume cells (a mesh is of volume cells or of surface cells)");
    if (soup.cell_offset[c + 1] - soup.cell_offset[c] != std::uint64_t(d.num_vertices))
      throw InputError(soup.source, cell_place(soup, c), "wrong number of vertices for its type");
    const auto v = soup.cell(c);
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (v[i] >= soup.points.size())
        throw InputError(soup.source, cell_place(soup, c), "vertex index " + std::to_string(v[i] + 1) + " out of range");
      for (std::size_t j = 0; j < i; ++j)
        if (v[j] == v[i])
          throw InputError(soup.source, cell_place(soup, c),
                           "vertex " + std::to_string(v[i] + 1) + " appears twice (a collapsed cell)");
    }
  }
  m.cell_face_off_.assign(1, 0);
  m.cell_edge_off_.assign(1, 0);
  for (CellType t : m.cell_type_) {
    m.cell_face_off_.push_back(m.cell_face_off_.back() + std::uint64_t(m.dim_ == 3 ? descriptor(t).num_faces : 0));
    m.cell_edge_off_.push_back(m.cell_edge_off_.back() + std::uint64_t(descriptor(t).num_edges));
  }
}

void PrimalMeshBuilder::build_vertex_stars(PrimalMesh& m) {
  m.vstar_off_.assign(m.num_vertices() + 1, 0);
  for (VertexId v : m.cell_vtx_) ++m.vstar_off_[v.idx + 1];
  for (std::size_t v = 0; v < m.num_vertices(); ++v) m.vstar_off_[v + 1] += m.vstar_off_[v];
  m.vstar_.resize(m.cell_vtx_.size());
  std::vector<std::uint64_t> at(m.vstar_off_.begin(), m.vstar_off_.end() - 1);
  for (std::size_t c = 0; c < m.num_cells(); ++c)  // cells in increasing order: each star comes out sorted
    for (VertexId v : m.cell_vertices(PrimalCellId(c))) m.vstar_[at[v.idx]++] = PrimalCellId(c);
}

}  // namespace polydual
