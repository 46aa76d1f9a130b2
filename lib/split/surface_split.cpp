#include "split/surface_split.h"

#include <map>

#include "core/interrupt.h"
#include "dual/surface_dual.h"

namespace polydual {

namespace {

bool touches(const PrimalMesh& m, const std::vector<char>& whole, PrimalCellId c) {
  for (VertexId v : m.cell_vertices(c))
    if (whole[v.idx]) return true;
  return false;
}

// Marks the vertices of the invalid polygons whole; returns how many were new.
std::size_t cut_invalid(const PrimalMesh& m, const PolySurface& dual, const SurfaceVerdicts& verdicts,
                        const std::vector<VertexId>& vertex_of_input, std::vector<char>& whole) {
  std::size_t added = 0;
  for (std::size_t i = 0; i < dual.num_polygons(); ++i) {
    if (verdicts.valid[i]) continue;
    const VertexId v = vertex_of_input[dual.primal_vertex(i)];
    if (!whole[v.idx]) whole[v.idx] = 1, ++added;
  }
  return added;
}

}  // namespace

std::size_t warm_start_surface(const PrimalMesh& m, const std::vector<char>& whole, const PolySurface& before,
                               PolySurface& after) {
  std::map<std::uint32_t, Point3> centre;
  for (std::size_t p = 0; p < before.num_points(); ++p)
    if (before.point_origin(p).kind == SurfacePointOrigin::Kind::CellCentre)
      centre.emplace(before.point_origin(p).id, before.point(p));
  std::size_t moved = 0;
  for (std::size_t p = 0; p < after.num_points(); ++p) {
    const SurfacePointOrigin o = after.point_origin(p);
    if (o.kind != SurfacePointOrigin::Kind::CellCentre || touches(m, whole, PrimalCellId(o.id))) continue;
    if (const auto it = centre.find(o.id); it != centre.end()) after.set_point(p, it->second), ++moved;
  }
  return moved;
}

Json run_surface_split(const PrimalMesh& m, const SplitParams& params, const SurfaceSmoother& smooth,
                       PolySurface& dual, SurfaceVerdicts& verdicts) {
  std::vector<VertexId> vertex_of_input;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const std::uint64_t in = m.input_vertex(VertexId(v));
    if (in >= vertex_of_input.size()) vertex_of_input.resize(in + 1, VertexId::invalid());
    vertex_of_input[in] = VertexId(std::uint32_t(v));
  }
  std::vector<char> whole(m.num_vertices(), 0);
  const std::size_t invalid_before = verdicts.invalid, polygons_before = dual.num_polygons();
  int rounds = 0;
  std::size_t cut = 0;
  while (verdicts.invalid > 0 && rounds < params.max_rounds) {
    throw_if_interrupted();
    const std::size_t added = cut_invalid(m, dual, verdicts, vertex_of_input, whole);
    if (added == 0) break;
    PolySurface fresh = build_surface_dual(m, &whole);
    warm_start_surface(m, whole, dual, fresh);
    if (smooth) smooth(fresh);
    dual = std::move(fresh);
    verdicts = surface_verdicts(dual);
    cut += added;
    ++rounds;
  }
  Json stats = Json::object();
  stats.set("rounds", rounds);
  stats.set("whole_vertices", cut);
  stats.set("invalid_before", invalid_before);
  stats.set("invalid_after", verdicts.invalid);
  stats.set("polygons_before", polygons_before);
  stats.set("polygons_after", dual.num_polygons());
  return stats;
}

}  // namespace polydual
