#include "dual/sides.h"

#include "classify/union_find.h"

namespace polydual {

VertexSides compute_sides(const ClassifiedTetMesh& m) {
  const std::size_t nt = m.num_tets();
  // Corners (t, i) -> 4t+i; join corners of the same primal vertex across
  // triangles that are not on a model face.
  UnionFind uf(4 * nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tv = m.tet(TetId(t));
    for (int j = 0; j < 4; ++j) {
      TetId s = m.tet_neighbor(TetId(t), j);
      if (!s.valid() || s.idx < t || m.on_model_face(m.tet_triangle(TetId(t), j))) continue;
      for (int i = 0; i < 4; ++i) {
        if (i == j) continue;
        uf.unite(4 * t + i, 4 * s.idx + m.local_index(s, tv[i]));
      }
    }
  }
  VertexSides out;
  out.cell_of.assign(4 * nt, CellId::invalid());
  std::vector<CellId> root_cell(4 * nt, CellId::invalid());
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    for (TetId t : m.vertex_tets(VertexId(v))) {
      const int i = m.local_index(t, VertexId(v));
      const std::uint32_t r = uf.find(4 * t.idx + i);
      if (!root_cell[r].valid()) {
        root_cell[r] = CellId(out.num_cells++);
        out.cell_vertex.push_back(VertexId(v));
        out.cell_material.push_back(m.region(t));
      }
      out.cell_of[4 * t.idx + i] = root_cell[r];
    }
  }
  return out;
}

}  // namespace polydual
