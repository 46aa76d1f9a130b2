#include "dual/sides.h"

#include <algorithm>
#include <type_traits>

namespace polydual {

VertexSides compute_sides(const ClassifiedTetMesh& m, const VertexCuts* cuts) {
  const std::size_t nv = m.num_vertices();
  VertexSides out;
  out.mesh = &m;
  out.first_cell.resize(nv);
  out.corner_off.assign(nv, VertexSides::kOneSide);
  out.cell_vertex.reserve(nv + nv / 4);
  out.cell_material.reserve(nv + nv / 4);
  // Per vertex v, a union-find over the positions of its star (sorted by tet):
  // tets sharing a triangle through v that is not on a model face join.
  std::vector<std::uint32_t> parent, root_cell;
  struct Join { std::uint32_t k; TetId s; };
  std::vector<Join> joins;
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t vi = 0; vi < nv; ++vi) {
    const VertexId v(vi);
    const std::span<const TetId> star = m.vertex_tets(v);
    out.first_cell[vi] = std::uint32_t(out.num_cells);
    const std::span<const TriId> cut = cuts ? cuts->of(v) : std::span<const TriId>{};
    // A vertex on no model face (classified in a region) and without cuts
    // has a single side.
    if (m.vertex_class(v).dim == 3 && cut.empty()) {
      ++out.num_cells;
      out.cell_vertex.push_back(v);
      out.cell_material.push_back(m.region(star.front()));
      continue;
    }
    const std::uint32_t n = std::uint32_t(star.size());
    parent.resize(n);
    for (std::uint32_t k = 0; k < n; ++k) parent[k] = k;
    // Joins with a later neighbour across a triangle that is not on a model
    // face nor in v's cuts. Which faces join is a coin toss along a boundary: the pairs are
    // gathered without branches (written always, counted by the flag), then
    // united.
    joins.resize(3 * std::size_t(n));
    std::size_t nj = 0;
    auto gather = [&](auto with_cuts) {
      for (std::uint32_t k = 0; k < n; ++k) {
        const TetId t = star[k];
        const int iv = m.local_index(t, v);
        for (int q = 0; q < 3; ++q) {
          const int j = (iv + 1 + q) & 3;  // the three faces through v
          const TetId s = m.tet_neighbor(t, j);
          joins[nj] = {k, s};
          const TriId f = m.tet_triangle(t, j);
          unsigned join = unsigned(s.valid()) & unsigned(s.idx > t.idx) & unsigned(!m.on_model_face(f));
          if constexpr (decltype(with_cuts)::value) join &= unsigned(!cuts->cuts(v, f));
          nj += join;
        }
      }
    };
    // A vertex without cuts runs the loop without the cut test.
    if (cut.empty()) gather(std::false_type{});
    else gather(std::true_type{});
    for (std::size_t q = 0; q < nj; ++q) {
      const std::uint32_t a = find(joins[q].k), b = find(m.star_rank(v, joins[q].s));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
    out.corner_off[vi] = std::uint32_t(out.corner_cell.size());
    root_cell.assign(n, CellId::kInvalid);
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t r = find(k);
      if (root_cell[r] == CellId::kInvalid) {
        root_cell[r] = std::uint32_t(out.num_cells++);
        out.cell_vertex.push_back(v);
        out.cell_material.push_back(m.region(star[k]));
      }
      out.corner_cell.push_back(CellId(root_cell[r]));
    }
  }
  return out;
}

}  // namespace polydual
