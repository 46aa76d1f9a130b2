#include "split/warm_start.h"

#include <algorithm>
#include <unordered_map>

#include "dual/cut_topology.h"
#include "dual/sides.h"

namespace polydual {

namespace {
std::uint64_t origin_key(PointOrigin o) { return (std::uint64_t(std::uint8_t(o.dim)) << 32) | o.id; }
}  // namespace

std::size_t warm_start(PolyMesh& fresh, const PolyMesh& old, const ClassifiedTetMesh& m, const VertexCuts& cuts) {
  if (fresh.point_origin.size() != fresh.points.size() || old.point_origin.size() != old.points.size()) return 0;
  constexpr std::uint32_t kShared = 0xffffffffu;
  std::unordered_map<std::uint64_t, std::uint32_t> where;
  where.reserve(old.points.size());
  for (std::size_t i = 0; i < old.points.size(); ++i) {
    if (old.point_origin[i].dim < 0) continue;
    auto [it, inserted] = where.emplace(origin_key(old.point_origin[i]), std::uint32_t(i));
    if (!inserted) it->second = kShared;
  }
  std::size_t moved = 0;
  for (std::size_t i = 0; i < fresh.points.size(); ++i) {
    if (fresh.point_origin[i].dim < 0 || pinned(m, &cuts, fresh.point_origin[i])) continue;
    const auto it = where.find(origin_key(fresh.point_origin[i]));
    if (it == where.end() || it->second == kShared) continue;
    fresh.points[i] = old.points[it->second];
    ++moved;
  }
  return moved;
}

std::vector<CellId> cut_cell_origins(const ClassifiedTetMesh& m, const VertexCuts& cuts, const PolyMesh& mesh) {
  const VertexSides plain = compute_sides(m, nullptr), cut = compute_sides(m, &cuts);
  if (cut.num_cells != mesh.num_cells()) return {};
  std::vector<CellId> origin(mesh.num_cells(), CellId::invalid());
  for (std::size_t vi = 0; vi < m.num_vertices(); ++vi) {
    const VertexId v(vi);
    for (TetId t : m.vertex_tets(v)) origin[cut.cell(t, v).idx] = plain.cell(t, v);
  }
  for (std::size_t c = 0; c < origin.size(); ++c)
    if (!origin[c].valid() || mesh.cell_primal[c] != VertexId(m.input_vertex(cut.cell_vertex[c]))) return {};
  return origin;
}

}  // namespace polydual
