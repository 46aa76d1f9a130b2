#include "split/local_round.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/stopwatch.h"
#include "mesh/sub_mesh.h"
#include "quality/star_verdict.h"
#include "split/cuts.h"

namespace polydual {

namespace {

// N[changed] without the vertices cut whole, increasing.
std::vector<VertexId> closed_neighbourhood(const ClassifiedTetMesh& m, std::span<const VertexId> changed,
                                           std::span<const char> whole, std::vector<char>& mark) {
  mark.assign(m.num_vertices(), 0);
  for (VertexId d : changed)
    for (TetId t : m.vertex_tets(d))
      for (VertexId w : m.tet(t)) mark[w.idx] = !whole[w.idx];
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

}  // namespace

VertexCuts restrict_cuts(const ClassifiedTetMesh& m, const SubMesh& s, const VertexCuts& cuts) {
  if (cuts.empty()) return {};
  std::vector<std::uint32_t> sub_of(m.num_tets(), std::uint32_t(-1));
  for (std::size_t t = 0; t < s.tet.size(); ++t) sub_of[s.tet[t].idx] = std::uint32_t(t);
  std::vector<std::pair<VertexId, TriId>> pairs;
  for (std::size_t v = 0; v < s.vertex.size(); ++v)
    for (TriId f : cuts.of(s.vertex[v])) {
      const TriId g = sub_triangle(m, s, sub_of, f);
      if (g.valid()) pairs.emplace_back(VertexId(v), g);
    }
  VertexCuts out = VertexCuts::from_pairs(s.mesh.num_vertices(), std::move(pairs));
  if (cuts.any_whole()) {
    out.whole.assign(s.vertex.size(), 0);
    for (std::size_t v = 0; v < s.vertex.size(); ++v) out.whole[v] = cuts.is_whole(s.vertex[v]);
  }
  return out;
}

namespace {

// The cuts of ld's mesh: `free` (its free-edge cuts) and the whole cuts of
// the vertices marked in `whole` (m's numbering).
VertexCuts local_cuts(const LocalDual& ld, const ClassifiedTetMesh& m, const VertexCuts& free,
                      std::span<const char> whole) {
  if (ld.on_whole_mesh) return with_whole_cuts(m, free, whole);
  std::vector<char> here(ld.sub.vertex.size());
  for (std::size_t v = 0; v < here.size(); ++v) here[v] = whole[ld.sub.vertex[v].idx];
  return with_whole_cuts(ld.sub.mesh, free, here);
}

}  // namespace

LocalDual local_dual(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                     std::span<const VertexId> changed, const DualParams& params, double collapse_length,
                     double whole_mesh_share) {
  Stopwatch w;
  auto lap = [&](LocalDual& ld, const char* part) {
    ld.seconds.set(part, w.seconds());
    w = Stopwatch();
  };
  if (whole.size() != m.num_vertices())
    throw std::logic_error("local_dual: " + std::to_string(whole.size()) + " whole flags for " +
                           std::to_string(m.num_vertices()) + " vertices");
  std::vector<char> in_u;
  const std::vector<VertexId> u = closed_neighbourhood(m, changed, whole, in_u);
  LocalDual out;
  if (u.empty()) {  // every neighbour cut whole: no cell to build (an empty sub-mesh)
    lap(out, "sub_mesh");
    return out;
  }
  std::vector<TetId> tets = star_tets(m, u);
  out.on_whole_mesh = double(tets.size()) > whole_mesh_share * double(m.num_tets());
  if (out.on_whole_mesh) {
    out.active = std::move(in_u);
  } else {
    out.sub = sub_mesh(m, tets);
    out.active.assign(out.sub.vertex.size(), 0);
    for (std::size_t v = 0; v < out.sub.vertex.size(); ++v) out.active[v] = in_u[out.sub.vertex[v].idx];
  }
  tets = std::vector<TetId>();
  lap(out, "sub_mesh");
  VertexCuts sub_free;
  if (!out.on_whole_mesh) sub_free = restrict_cuts(m, out.sub, free_edge);
  const VertexCuts cuts = local_cuts(out, m, out.on_whole_mesh ? free_edge : sub_free, whole);
  lap(out, "cuts");
  const DualScope scope{out.active, collapse_length};
  DualStats ds;
  out.dual = build_dual(out.mesh(m), params, &ds, &cuts, &scope);
  lap(out, "dual");
  const Json parts = ds.to_json();
  out.seconds.set("dual_parts", *parts.find("seconds"));
  return out;
}

LocalRound local_round(const ClassifiedTetMesh& m, const VertexCuts& free_edge, std::span<const char> whole,
                       std::span<const VertexId> changed, const DualParams& params, double collapse_length,
                       double whole_mesh_share) {
  LocalRound out;
  const LocalDual ld = local_dual(m, free_edge, whole, changed, params, collapse_length, whole_mesh_share);
  const ClassifiedTetMesh& mesh = ld.mesh(m);
  const PolyMesh& dual = ld.dual;
  out.seconds = ld.seconds;
  out.tets = mesh.num_tets();
  out.on_whole_mesh = ld.on_whole_mesh;
  Stopwatch w;
  // Cells are numbered by vertex (every vertex of a sub-mesh has a tet, so at
  // least one cell; on the whole mesh a vertex without one has no active
  // cell to find), then by side: a walk pairs them.
  std::vector<std::uint32_t> cells, cell_vertex;  // tested cell -> its vertex in `mesh`
  for (std::size_t c = 0, v = 0; c < dual.num_cells(); ++c) {
    while (v < mesh.num_vertices() && mesh.input_vertex(VertexId(v)) != dual.cell_primal[c].idx) ++v;
    if (v == mesh.num_vertices()) throw std::logic_error("local_round: cells not in vertex order");
    if (!ld.active[v]) continue;
    cells.push_back(std::uint32_t(c));
    cell_vertex.push_back(std::uint32_t(v));
  }
  std::vector<CellVerdict> verdicts(dual.num_cells());
  star_shaped_verdicts_of(dual, cells, verdicts, {});  // exact-fallback counts not needed
  out.cells_tested = cells.size();
  std::vector<std::uint32_t> bad(mesh.num_vertices(), 0);
  for (std::size_t i = 0; i < cells.size(); ++i) bad[cell_vertex[i]] += !verdicts[cells[i]].valid;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
    if (ld.active[v]) {
      out.vertices.push_back(ld.whole_vertex(v));
      out.invalid.push_back(bad[v]);
    }
  out.seconds.set("star_test", w.seconds());
  return out;
}

}  // namespace polydual
