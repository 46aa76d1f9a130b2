#include "split/surface_split.h"

#include <map>

#include "core/interrupt.h"
#include "dual/surface_dual.h"

namespace polydual {

namespace {

// Marks the vertices of the invalid polygons whole; returns how many were new.
std::size_t cut_invalid(const PolySurface& dual, const SurfaceVerdicts& verdicts,
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
    if (o.kind != SurfacePointOrigin::Kind::CellCentre || any_marked(m.cell_vertices(PrimalCellId(o.id)), whole)) continue;
    if (const auto it = centre.find(o.id); it != centre.end()) after.set_point(p, it->second), ++moved;
  }
  return moved;
}

Json run_surface_split(const PrimalMesh& m, const SplitParams& params, const SurfaceSmoother& smooth,
                       PolySurface& dual, SurfaceVerdicts& verdicts) {
  const std::vector<VertexId> vertex_of_input = internal_of_input(m);
  std::vector<char> whole(m.num_vertices(), 0);
  const std::size_t invalid_before = verdicts.invalid, polygons_before = dual.num_polygons();
  int rounds = 0;
  std::size_t cut = 0;
  while (verdicts.invalid > 0 && rounds < params.max_rounds) {
    throw_if_interrupted();
    const std::size_t added = cut_invalid(dual, verdicts, vertex_of_input, whole);
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
