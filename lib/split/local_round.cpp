#include "split/local_round.h"

#include <algorithm>

#include "core/stopwatch.h"
#include "mesh/sub_mesh.h"
#include "quality/star_verdict.h"
#include "split/cuts.h"

namespace polydual {

namespace {

// N[changed], increasing.
std::vector<VertexId> closed_neighbourhood(const ClassifiedTetMesh& m, std::span<const VertexId> changed,
                                           std::vector<char>& mark) {
  mark.assign(m.num_vertices(), 0);
  for (VertexId d : changed)
    for (TetId t : m.vertex_tets(d))
      for (VertexId w : m.tet(t)) mark[w.idx] = 1;
  std::vector<VertexId> out;
  for (std::size_t v = 0; v < mark.size(); ++v)
    if (mark[v]) out.push_back(VertexId(v));
  return out;
}

// The triangle of s.mesh that is whole-mesh triangle f, or invalid when one
// of f's tets is not in the sub-mesh (sub_of: whole tet -> sub tet).
TriId sub_triangle(const ClassifiedTetMesh& m, const SubMesh& s, const std::vector<std::uint32_t>& sub_of, TriId f) {
  const TetId t0 = m.triangle_tet(f, 0), t1 = m.triangle_tet(f, 1);
  if (!t1.valid() || sub_of[t0.idx] == std::uint32_t(-1) || sub_of[t1.idx] == std::uint32_t(-1)) return TriId::invalid();
  for (int i = 0; i < 4; ++i)
    if (m.tet_triangle(t0, i) == f) return s.mesh.tet_triangle(TetId(sub_of[t0.idx]), i);
  return TriId::invalid();
}

// The whole mesh's cuts restricted to the sub-mesh (see local_round).
VertexCuts sub_cuts(const ClassifiedTetMesh& m, const SubMesh& s, const VertexCuts& free_edge,
                    std::span<const char> whole) {
  std::vector<std::uint32_t> sub_of(m.num_tets(), std::uint32_t(-1));
  for (std::size_t t = 0; t < s.tet.size(); ++t) sub_of[s.tet[t].idx] = std::uint32_t(t);
  std::vector<std::pair<VertexId, TriId>> pairs;
  std::vector<VertexId> whole_here;
  for (std::size_t v = 0; v < s.vertex.size(); ++v) {
    const VertexId w = s.vertex[v];
    if (whole[w.idx]) whole_here.push_back(VertexId(v));
    for (TriId f : free_edge.of(w)) {
      const TriId g = sub_triangle(m, s, sub_of, f);
      if (g.valid()) pairs.emplace_back(VertexId(v), g);
    }
  }
  const std::size_t nv = s.mesh.num_vertices();
  return VertexCuts::merged(nv, VertexCuts::from_pairs(nv, std::move(pairs)), fallback_cuts(s.mesh, whole_here));
}

}  // namespace

LocalRound local_round(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                       std::span<const VertexId> changed, const DualParams& params, double collapse_length) {
  LocalRound out;
  Stopwatch w;
  auto lap = [&](const char* part) {
    out.seconds.set(part, w.seconds());
    w = Stopwatch();
  };
  std::vector<char> in_u;
  out.vertices = closed_neighbourhood(m, changed, in_u);
  const SubMesh s = sub_mesh(m, star_tets(m, out.vertices));
  out.tets = s.mesh.num_tets();
  std::vector<char> active(s.vertex.size(), 0);
  for (std::size_t v = 0; v < s.vertex.size(); ++v) active[v] = in_u[s.vertex[v].idx];
  lap("sub_mesh");
  const VertexCuts cuts = sub_cuts(m, s, free_edge, whole);
  lap("cuts");
  const DualScope scope{active, collapse_length};
  const PolyMesh dual = build_dual(s.mesh, params, nullptr, &cuts, &scope);
  lap("dual");
  // Cells are numbered by sub-mesh vertex (every vertex of a sub-mesh has a
  // tet, so at least one cell), then by side: a walk pairs them.
  std::vector<std::uint32_t> cells, cell_vertex;  // tested cell -> index in s.vertex
  for (std::size_t c = 0, v = 0; c < dual.num_cells(); ++c) {
    while (s.mesh.input_vertex(VertexId(v)) != dual.cell_primal[c].idx) ++v;
    if (!active[v]) continue;
    cells.push_back(std::uint32_t(c));
    cell_vertex.push_back(std::uint32_t(v));
  }
  std::vector<CellVerdict> verdicts(dual.num_cells());
  std::vector<std::uint32_t> exact(dual.num_cells(), 0);
  star_shaped_verdicts_of(dual, cells, verdicts, exact);
  out.cells_tested = cells.size();
  std::vector<std::uint32_t> bad(s.vertex.size(), 0);
  for (std::size_t i = 0; i < cells.size(); ++i) bad[cell_vertex[i]] += !verdicts[cells[i]].valid;
  out.invalid.reserve(out.vertices.size());
  for (std::size_t v = 0; v < s.vertex.size(); ++v)
    if (active[v]) out.invalid.push_back(bad[v]);
  lap("star_test");
  return out;
}

}  // namespace polydual
