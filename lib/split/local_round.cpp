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

LocalDual local_dual(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                     std::span<const VertexId> changed, const DualParams& params, double collapse_length) {
  Stopwatch w;
  std::vector<char> in_u;
  const std::vector<VertexId> u = closed_neighbourhood(m, changed, in_u);
  LocalDual out{sub_mesh(m, star_tets(m, u)), {}, {}, Json::object()};
  out.active.assign(out.sub.vertex.size(), 0);
  for (std::size_t v = 0; v < out.sub.vertex.size(); ++v) out.active[v] = in_u[out.sub.vertex[v].idx];
  out.seconds.set("sub_mesh", w.seconds());
  w = Stopwatch();
  const VertexCuts cuts = sub_cuts(m, out.sub, free_edge, whole);
  out.seconds.set("cuts", w.seconds());
  w = Stopwatch();
  const DualScope scope{out.active, collapse_length};
  out.dual = build_dual(out.sub.mesh, params, nullptr, &cuts, &scope);
  out.seconds.set("dual", w.seconds());
  return out;
}

LocalRound local_round(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                       std::span<const VertexId> changed, const DualParams& params, double collapse_length) {
  LocalRound out;
  const LocalDual ld = local_dual(m, free_edge, whole, changed, params, collapse_length);
  const SubMesh& s = ld.sub;
  const PolyMesh& dual = ld.dual;
  out.seconds = ld.seconds;
  Stopwatch w;
  out.tets = s.mesh.num_tets();
  // Cells are numbered by sub-mesh vertex (every vertex of a sub-mesh has a
  // tet, so at least one cell), then by side: a walk pairs them.
  std::vector<std::uint32_t> cells, cell_vertex;  // tested cell -> index in s.vertex
  for (std::size_t c = 0, v = 0; c < dual.num_cells(); ++c) {
    while (s.mesh.input_vertex(VertexId(v)) != dual.cell_primal[c].idx) ++v;
    if (!ld.active[v]) continue;
    cells.push_back(std::uint32_t(c));
    cell_vertex.push_back(std::uint32_t(v));
  }
  std::vector<CellVerdict> verdicts(dual.num_cells());
  std::vector<std::uint32_t> exact(dual.num_cells(), 0);
  star_shaped_verdicts_of(dual, cells, verdicts, exact);
  out.cells_tested = cells.size();
  std::vector<std::uint32_t> bad(s.vertex.size(), 0);
  for (std::size_t i = 0; i < cells.size(); ++i) bad[cell_vertex[i]] += !verdicts[cells[i]].valid;
  for (std::size_t v = 0; v < s.vertex.size(); ++v)
    if (ld.active[v]) {
      out.vertices.push_back(s.vertex[v]);
      out.invalid.push_back(bad[v]);
    }
  out.seconds.set("star_test", w.seconds());
  return out;
}

}  // namespace polydual
