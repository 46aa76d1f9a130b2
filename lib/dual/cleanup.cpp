#include "dual/cleanup.h"

#include "classify/union_find.h"

namespace polydual {

CleanupResult cleanup_dual(PolyMesh& pm, const std::vector<std::pair<PointId, PointId>>& exact_pairs,
                           double collapse_length) {
  CleanupResult res;
  const std::size_t np = pm.num_points(), nf = pm.num_faces();
  UnionFind uf(np);
  // Points merged exactly keep the coordinates of the smallest id (the root).
  for (auto [p, q] : exact_pairs) {
    if (pm.point_class[p.idx] != pm.point_class[q.idx]) continue;
    if (uf.find(p.idx) != uf.find(q.idx)) { uf.unite(p.idx, q.idx); ++res.merged_points; }
  }
  // Short edges, measured between the (merged) representatives. Inexact: a
  // length threshold is a tolerance, not a sign.
  if (collapse_length > 0) {
    const double lim2 = collapse_length * collapse_length;
    for (std::size_t f = 0; f < nf; ++f) {
      auto loop = pm.face(FaceId(f));
      for (std::size_t k = 0; k < loop.size(); ++k) {
        PointId p = loop[k], q = loop[(k + 1) % loop.size()];
        std::uint32_t rp = uf.find(p.idx), rq = uf.find(q.idx);
        if (rp == rq || pm.point_class[rp] != pm.point_class[rq]) continue;
        if (norm2(pm.points[rp] - pm.points[rq]) < lim2) { uf.unite(rp, rq); ++res.collapsed_points; }
      }
    }
  }
  // Compact the points that survive (roots used by a surviving face).
  std::vector<PointId> new_id(np, PointId::invalid());
  PolyMesh out;
  out.face_offsets = {0};
  std::vector<PointId> loop;
  for (std::size_t f = 0; f < nf; ++f) {
    loop.clear();
    for (PointId p : pm.face(FaceId(f))) {
      PointId r(uf.find(p.idx));
      if (loop.empty() || loop.back() != r) loop.push_back(r);
    }
    while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
    if (loop.size() < 3) { ++res.dropped_faces; continue; }
    for (PointId& r : loop) {
      if (!new_id[r.idx].valid()) new_id[r.idx] = out.add_point(pm.points[r.idx], pm.point_class[r.idx]);
      r = new_id[r.idx];
    }
    out.add_face(loop, pm.face_owner[f], pm.face_neighbour[f], pm.face_kind[f], pm.face_tag[f]);
  }
  out.cell_offsets = pm.cell_offsets;
  out.cell_material = std::move(pm.cell_material);
  out.cell_primal = std::move(pm.cell_primal);
  pm = std::move(out);
  return res;
}

}  // namespace polydual
