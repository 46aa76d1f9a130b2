#include "dual/cleanup.h"

#include "classify/union_find.h"

namespace polydual {

// Works in place (no second PolyMesh: the cleanup runs at the memory peak of
// the dual construction): loops only shrink and faces/points only disappear, so
// every write index is at most the read index.
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
  // Rewrite loops through the representatives, drop repeated consecutive
  // points and faces left with fewer than 3; mark the points still used.
  std::vector<char> used(np, 0);
  std::size_t out_f = 0, out_p = 0, read = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const std::size_t begin = read, end = pm.face_offsets[f + 1];
    read = end;
    const std::size_t start = out_p;
    for (std::size_t i = begin; i < end; ++i) {
      const PointId r(uf.find(pm.face_points[i].idx));
      if (out_p == start || pm.face_points[out_p - 1] != r) pm.face_points[out_p++] = r;
    }
    while (out_p - start > 1 && pm.face_points[start] == pm.face_points[out_p - 1]) --out_p;
    if (out_p - start < 3) { out_p = start; ++res.dropped_faces; continue; }
    for (std::size_t i = start; i < out_p; ++i) used[pm.face_points[i].idx] = 1;
    pm.face_offsets[out_f + 1] = static_cast<std::uint32_t>(out_p);
    pm.face_owner[out_f] = pm.face_owner[f];
    pm.face_neighbour[out_f] = pm.face_neighbour[f];
    pm.face_kind[out_f] = pm.face_kind[f];
    pm.face_tag[out_f] = pm.face_tag[f];
    ++out_f;
  }
  pm.face_points.resize(out_p);
  pm.face_offsets.resize(out_f + 1);
  pm.face_owner.resize(out_f);
  pm.face_neighbour.resize(out_f);
  pm.face_kind.resize(out_f);
  pm.face_tag.resize(out_f);
  // Compact the used points, keeping their order: points before the first
  // unused one keep their ids (often all of them: then nothing moves).
  std::size_t first_unused = 0;
  while (first_unused < np && used[first_unused]) ++first_unused;
  if (first_unused == np) return res;
  std::vector<PointId> new_id(np - first_unused, PointId::invalid());
  std::size_t k = first_unused;
  for (std::size_t p = first_unused; p < np; ++p) {
    if (!used[p]) continue;
    new_id[p - first_unused] = PointId(k);
    pm.points[k] = pm.points[p];
    pm.point_class[k] = pm.point_class[p];
    ++k;
  }
  pm.points.resize(k);
  pm.point_class.resize(k);
  for (PointId& p : pm.face_points)
    if (p.idx >= first_unused) p = new_id[p.idx - first_unused];
  pm.points.shrink_to_fit();
  pm.point_class.shrink_to_fit();
  return res;
}

}  // namespace polydual
