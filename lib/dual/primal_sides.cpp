#include "dual/primal_sides.h"

#include <algorithm>

#include "core/union_find.h"

namespace polydual {

CellId PrimalSides::cell_in_star(const PrimalMesh& m, PrimalCellId c, VertexId v) const {
  const auto star = m.vertex_cells(v);
  const auto it = std::lower_bound(star.begin(), star.end(), c);
  return corner_cell[star_off[v.idx] + std::uint64_t(it - star.begin())];
}

namespace {

// Whether local face i of cell c (descriptor d) has local vertex iv.
bool face_has(const CellDescriptor& d, int i, int iv) {
  for (int k = 0; k < d.face_size[i]; ++k)
    if (d.faces[i][k] == iv) return true;
  return false;
}

}  // namespace

PrimalSides compute_primal_sides(const PrimalMesh& m, const std::vector<char>* whole) {
  const std::size_t nv = m.num_vertices();
  PrimalSides out;
  out.star_off.resize(nv + 1, 0);
  for (std::size_t v = 0; v < nv; ++v) out.star_off[v + 1] = out.star_off[v] + m.vertex_cells(VertexId(v)).size();
  out.corner_cell.resize(out.star_off[nv]);
  out.single.assign(nv, CellId::invalid());
  std::vector<std::uint32_t> root_cell;
  for (std::size_t vi = 0; vi < nv; ++vi) {
    const VertexId v(vi);
    const auto star = m.vertex_cells(v);
    const std::uint32_t n = std::uint32_t(star.size());
    // A vertex cut whole: one side per cell.
    if (whole && (*whole)[vi]) {
      for (std::uint32_t k = 0; k < n; ++k) {
        out.corner_cell[out.star_off[vi] + k] = CellId(std::uint32_t(out.num_cells++));
        out.cell_vertex.push_back(v);
        out.cell_material.push_back(m.cell_class(star[k]).tag);
      }
      continue;
    }
    // A vertex classified in a region has no model face through it: one side.
    if (m.vertex_class(v).dim == 3) {
      for (std::uint32_t k = 0; k < n; ++k) out.corner_cell[out.star_off[vi] + k] = CellId(out.num_cells);
      out.single[vi] = CellId(out.num_cells++);
      out.cell_vertex.push_back(v);
      out.cell_material.push_back(m.cell_class(star.front()).tag);
      continue;
    }
    // Cells sharing a face through v that is on no model face join.
    UnionFind uf(n);
    for (std::uint32_t k = 0; k < n; ++k) {
        const PrimalCellId c = star[k];
        const CellDescriptor& d = m.cell_descriptor(c);
        const int iv = m.local_index(c, v);
        for (int i = 0; i < d.num_faces; ++i) {
          if (!face_has(d, i, iv) || m.face_class(m.cell_face(c, i)).dim == 2) continue;
          const PrimalCellId s = m.cell_neighbor(c, i);
          if (!s.valid() || s.idx < c.idx) continue;
          const auto it = std::lower_bound(star.begin(), star.end(), s);
          uf.unite(k, std::uint32_t(it - star.begin()));
        }
      }
    root_cell.assign(n, CellId::kInvalid);
    const std::size_t first = out.num_cells;
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t r = uf.find(k);
      if (root_cell[r] == CellId::kInvalid) {
        root_cell[r] = std::uint32_t(out.num_cells++);
        out.cell_vertex.push_back(v);
        out.cell_material.push_back(m.cell_class(star[k]).tag);
      }
      out.corner_cell[out.star_off[vi] + k] = CellId(root_cell[r]);
    }
    if (out.num_cells == first + 1) out.single[vi] = CellId(std::uint32_t(first));
  }
  return out;
}

}  // namespace polydual
