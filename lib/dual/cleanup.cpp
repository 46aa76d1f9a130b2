#include "dual/cleanup.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "core/union_find.h"

namespace polydual {

namespace {

// Rewrites the loops of the faces in `touched` (sorted face ids) through
// their representatives, drops repeated consecutive points and faces left with fewer than 3,
// and moves every later face down over what was removed. Faces before and
// between the touched ones are moved as blocks (one memmove and a shift of
// their offsets): merges are rare, so almost all the work is block copies.
// In place: faces and points only disappear, so writes never pass reads.
std::size_t rewrite_touched_faces(PolyMesh& pm, const std::vector<std::uint32_t>& touched, UnionFind& uf) {
  std::size_t dropped = 0;
  const std::size_t nf = pm.num_faces();
  if (touched.empty()) return 0;
  auto& off = pm.face_offsets;
  auto& fp = pm.face_points;
  std::size_t wf = touched.front(), wp = off[wf];  // write cursors: next face, next point
  std::size_t rf = wf;                              // read cursor: next face
  std::size_t read_start = off[rf];                 // original start of face rf
  auto copy_face_data = [&](std::size_t to, std::size_t from) {
    pm.face_owner[to] = pm.face_owner[from];
    pm.face_neighbour[to] = pm.face_neighbour[from];
    pm.face_kind[to] = pm.face_kind[from];
    pm.face_tag[to] = pm.face_tag[from];
  };
  // Faces [rf, upto) unchanged: one block.
  auto move_block = [&](std::size_t upto) {
    if (upto == rf) return;
    const std::size_t end = off[upto];
    const std::size_t shift = read_start - wp;
    if (shift != 0) std::memmove(fp.data() + wp, fp.data() + read_start, (end - read_start) * sizeof(PointId));
    if (shift != 0 || wf != rf)
      for (std::size_t f = rf; f < upto; ++f, ++wf) {
        off[wf + 1] = static_cast<std::uint32_t>(off[f + 1] - shift);
        copy_face_data(wf, f);
      }
    else
      wf += upto - rf;
    wp += end - read_start;
    rf = upto;
    read_start = end;
  };
  for (std::uint32_t f : touched) {
    move_block(f);
    const std::size_t end = off[f + 1];
    const std::size_t start = wp;
    for (std::size_t i = read_start; i < end; ++i) {
      const PointId r(uf.find(fp[i].idx));
      if (wp == start || fp[wp - 1] != r) fp[wp++] = r;
    }
    while (wp - start > 1 && fp[start] == fp[wp - 1]) --wp;
    rf = f + 1;
    read_start = end;
    if (wp - start < 3) {
      wp = start;
      ++dropped;
      continue;
    }
    off[wf + 1] = static_cast<std::uint32_t>(wp);
    copy_face_data(wf, f);
    ++wf;
  }
  move_block(nf);
  fp.resize(wp);
  off.resize(wf + 1);
  pm.face_owner.resize(wf);
  pm.face_neighbour.resize(wf);
  pm.face_kind.resize(wf);
  pm.face_tag.resize(wf);
  return dropped;
}

// The exact coincidences: points of equal classification are united (the
// smaller id is the root and keeps its coordinates).
std::size_t merge_exact_pairs(const PolyMesh& pm, const std::vector<std::pair<PointId, PointId>>& pairs,
                              UnionFind& uf) {
  std::size_t merged = 0;
  for (auto [p, q] : pairs) {
    if (pm.point_class[p.idx] != pm.point_class[q.idx]) continue;
    if (uf.find(p.idx) != uf.find(q.idx)) { uf.unite(p.idx, q.idx); ++merged; }
  }
  return merged;
}

// Short edges, measured between the (merged) representatives: first the
// listed pairs, then in the loops of scan_faces edge by edge (p_k, p_k+1 mod
// n); each point's representative is found once and carried to the next edge.
// Inexact: a length threshold is a tolerance, not a sign.
std::size_t collapse_short_edges(const PolyMesh& pm, const DualDraft& d, UnionFind& uf) {
  std::size_t collapsed = 0;
  if (!(d.collapse_length > 0)) return 0;
  const double lim2 = d.collapse_length * d.collapse_length;
  // Only points classified on the entity they come from collapse: a tet
  // centre, a model-face triangle centre, a model-edge midpoint, a model
  // vertex. The points that cuts add (cut triangle centres, midpoints of
  // other edges, other vertices) are classified on an entity of higher
  // dimension and keep the cut surface where the builder put it.
  const auto& origin = pm.point_origin;
  // Points pinned by a whole-cut vertex (C5) never collapse either.
  // With the boundary kept (DualDraft::keep_boundary) only tet centres do.
  auto own = [&](std::uint32_t p) {
    return (origin.empty() || origin[p].dim == pm.point_class[p].dim) && (d.pinned.empty() || !d.pinned[p]) &&
           (!d.keep_boundary || pm.point_class[p].dim == 3);
  };
  // The length test comes first: it is almost always false, and the classes
  // are then never loaded.
  auto check = [&](std::uint32_t rp, std::uint32_t rq) {
    if (norm2(pm.points[rp] - pm.points[rq]) < lim2 && rp != rq && pm.point_class[rp] == pm.point_class[rq] &&
        own(rp) && own(rq)) [[unlikely]] {
      uf.unite(rp, rq);
      ++collapsed;
      return uf.find(rq);
    }
    return rq;
  };
  for (auto [p, q] : d.short_pairs) check(uf.find(p.idx), uf.find(q.idx));
  const PointId* fp = pm.face_points.data();
  for (std::uint32_t f : d.scan_faces) {
    const std::size_t b = pm.face_offsets[f], e = pm.face_offsets[f + 1];
    std::uint32_t rp = uf.find(fp[b].idx);
    for (std::size_t i = b + 1; i < e; ++i) rp = check(rp, uf.find(fp[i].idx));
    check(rp, uf.find(fp[b].idx));  // the closing edge
  }
  return collapsed;
}

// The faces whose loops change (sorted ids): those with a merged point, and
// (merges or not) those with fewer than 3 points or a point repeated
// consecutively. Flat passes over all loops: a face is looked up only on a hit.
std::vector<std::uint32_t> faces_to_rewrite(const PolyMesh& pm, bool merged, UnionFind& uf) {
  const std::size_t np = pm.num_points(), nf = pm.num_faces();
  // moved[p]: p was merged into another point (one byte a point: the flat
  // pass below reads it for every loop entry).
  std::vector<char> moved(merged ? np : 0, 0);
  for (std::size_t p = 0; p < moved.size(); ++p) moved[p] = char(uf.find(p) != p);
  const auto& off = pm.face_offsets;
  const auto& fp = pm.face_points;
  std::vector<char> flag(nf, 0);
  for (std::size_t f = 0; f < nf; ++f)
    flag[f] = char((off[f + 1] - off[f] < 3) | (fp[off[f]] == fp[off[f + 1] - 1]));
  // Hits are rare: the face of position i is found by a cursor that only
  // moves forwards (hits come in increasing i).
  std::size_t cursor = 0;
  const std::size_t n = fp.size();
  for (std::size_t i = 0; i < n; ++i) {
    const bool dup = i + 1 < n && fp[i] == fp[i + 1];
    const bool mv = merged && moved[fp[i].idx];
    if (dup | mv) [[unlikely]] {
      while (off[cursor + 1] <= i) ++cursor;
      if (mv || off[cursor + 1] != i + 1) flag[cursor] = 1;  // a repeat across two faces is no repeat
    }
  }
  std::vector<std::uint32_t> touched;
  for (std::size_t f = 0; f < nf; ++f)
    if (flag[f]) [[unlikely]] touched.push_back(std::uint32_t(f));
  return touched;
}

// Drops the points no face uses, keeping the order: points before the first
// unused one keep their ids (usually all of them: then nothing moves).
// Returns the number dropped. shrink: the arrays may be shrunk.
std::size_t drop_unused_points(PolyMesh& pm, bool shrink) {
  const std::size_t np = pm.num_points();
  std::vector<char> used(np, 0);
  for (PointId p : pm.face_points) used[p.idx] = 1;
  std::size_t first_unused = 0;
  while (first_unused < np && used[first_unused]) ++first_unused;
  if (first_unused == np) return 0;
  // The new id of every point (the identity below first_unused): the loops
  // are then remapped by one lookup per entry, with no branch on the id.
  std::vector<std::uint32_t> new_id(np);
  for (std::size_t p = 0; p < first_unused; ++p) new_id[p] = std::uint32_t(p);
  std::size_t k = first_unused;
  for (std::size_t p = first_unused; p < np; ++p) {
    new_id[p] = std::uint32_t(k);  // for an unused point: never looked up
    if (!used[p]) continue;
    pm.points[k] = pm.points[p];
    pm.point_class[k] = pm.point_class[p];
    if (!pm.point_origin.empty()) pm.point_origin[k] = pm.point_origin[p];
    ++k;
  }
  pm.points.resize(k);
  pm.point_class.resize(k);
  if (!pm.point_origin.empty()) pm.point_origin.resize(k);
  for (PointId& p : pm.face_points) p = PointId(new_id[p.idx]);
  // Shrinking copies each array while the old one is alive, at the memory
  // peak of the build: worth it only when much was dropped, and never for a
  // short-lived (scoped) dual.
  if (shrink && 8 * (np - k) > np) {
    pm.points.shrink_to_fit();
    pm.point_class.shrink_to_fit();
    pm.point_origin.shrink_to_fit();
  }
  return np - k;
}

using Clock = std::chrono::steady_clock;

}  // namespace

Json CleanupStats::to_json() const {
  Json j = Json::object();
  j.set("merged_points", merged_points);
  j.set("collapsed_points", collapsed_points);
  j.set("dropped_faces", dropped_faces);
  j.set("dropped_points", dropped_points);
  j.set("seconds", seconds);
  return j;
}

// Flattened: the phases above are one kernel over the loops and the union-find;
// compiled as one function they take ~2% fewer instructions (callgrind) than
// as calls.
[[gnu::flatten]] CleanupStats cleanup_dual(DualDraft& d) {
  const auto t0 = Clock::now();
  CleanupStats st;
  PolyMesh& pm = d.mesh;
  UnionFind uf(pm.num_points());
  st.merged_points = merge_exact_pairs(pm, d.exact_pairs, uf);
  st.collapsed_points = collapse_short_edges(pm, d, uf);
  d.exact_pairs = {};
  d.short_pairs = {};
  d.scan_faces = {};
  d.pinned = {};
  const bool merged = st.merged_points + st.collapsed_points > 0;
  st.dropped_faces = rewrite_touched_faces(pm, faces_to_rewrite(pm, merged, uf), uf);
  st.dropped_points = drop_unused_points(pm, !d.scoped);
  st.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return st;
}

}  // namespace polydual
