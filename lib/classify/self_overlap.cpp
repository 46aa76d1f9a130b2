// The self-overlap check (self_overlap.h; the argument is proofs/self_overlap.md
// L15). Every decision is exact: coordinates are compared as doubles,
// orientations come from lib/predicates (orient3d, orient2d inside a
// coordinate plane, orient3d_centroid, CGAL's filtered do_intersect).
// Hashes, boxes and grid cells only choose which pairs to test; boxes and
// cells are built from the input doubles by monotone maps, so two triangles
// that meet always share a cell and their boxes always meet.
#include "classify/self_overlap.h"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "classify/triangle_crossing.h"
#include "core/error.h"
#include "core/radix_sort.h"
#include "core/union_find.h"
#include "predicates/predicates.h"

namespace polydual {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// A boundary triangle: the local face i of tet t, its vertices in the order
// whose right-hand normal points out of t (kTetFace).
struct BoundaryFace {
  std::array<VertexId, 3> v;
  TetId t;
  int i;
};
using FacePair = std::pair<std::uint32_t, std::uint32_t>;  // indices into the boundary faces

std::string vertex_number(const ClassifiedTetMesh& m, VertexId v) { return std::to_string(m.input_vertex(v) + 1); }
std::string tet_number(const ClassifiedTetMesh& m, TetId t) { return std::to_string(m.input_tet(t) + 1); }

// "tet 3 uses" / "tets 3, 8, 9, 11, ... use" (file numbering, at most 4).
std::string tets_using(const ClassifiedTetMesh& m, VertexId v) {
  std::vector<std::uint32_t> ids;
  for (TetId t : m.vertex_tets(v)) ids.push_back(m.input_tet(t) + 1);
  std::sort(ids.begin(), ids.end());
  std::string s = ids.size() == 1 ? "tet " : "tets ";
  for (std::size_t k = 0; k < ids.size() && k < 4; ++k) s += (k ? ", " : "") + std::to_string(ids[k]);
  return s + (ids.size() > 4 ? ", ..." : "") + (ids.size() == 1 ? " uses" : " use");
}

// ---- 1. Coincident vertices. The points are sorted by a 32-bit hash of
// their exact coordinates (a radix sort; -0.0 taken as 0.0), so equal points
// form runs of one hash; each run is sorted on the exact coordinates and
// then the file's numbering, so equal points end up side by side, the
// smallest numbers first. The pair reported is the one with the smallest
// file numbers: the same every run.

std::uint64_t mix(std::uint64_t x) {  // splitmix64's finaliser
  x ^= x >> 30; x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27; x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
std::uint32_t coordinate_hash(const Point3& p) {
  auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x == 0.0 ? 0.0 : x); };
  return std::uint32_t(mix(bits(p.x) ^ mix(bits(p.y) ^ mix(bits(p.z)))) >> 32);
}

[[noreturn, gnu::cold]] void throw_coincident(const ClassifiedTetMesh& m, VertexId a, VertexId b) {
  const Point3& p = m.point(a);
  char at[96];
  std::snprintf(at, sizeof at, "(%.17g, %.17g, %.17g)", p.x, p.y, p.z);
  throw InputError(m.source(), "vertex " + vertex_number(m, a),
                   "vertices " + vertex_number(m, a) + " and " + vertex_number(m, b) + " are at the same position " +
                       at + "; " + tets_using(m, a) + " vertex " + vertex_number(m, a) + " and " + tets_using(m, b) +
                       " vertex " + vertex_number(m, b) +
                       ": the mesh overlaps itself or holds a crack (a fracture or sheet is given by triangles "
                       "shared by the tets on both sides, tagged as a model face, not by duplicated vertices)");
}

void check_coincident_vertices(const ClassifiedTetMesh& m) {
  struct Rec { std::uint32_t hash, v; };
  std::vector<Rec> recs(m.num_vertices());
  for (std::size_t v = 0; v < recs.size(); ++v) recs[v] = {coordinate_hash(m.point(VertexId(v))), std::uint32_t(v)};
  radix_sort_by_key(recs, [](const Rec& r) { return r.hash; }, 32);
  auto exact_order = [&](const Rec& x, const Rec& y) {
    const Point3 &p = m.point(VertexId(x.v)), &q = m.point(VertexId(y.v));
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return m.input_vertex(VertexId(x.v)) < m.input_vertex(VertexId(y.v));
  };
  std::optional<std::pair<std::uint32_t, std::uint32_t>> first;  // file numbers (lower, higher)
  VertexId fa, fb;
  for (std::size_t s = 0, e = 0; s < recs.size(); s = e) {
    for (e = s + 1; e < recs.size() && recs[e].hash == recs[s].hash;) ++e;
    if (e - s > 1) std::sort(recs.begin() + std::ptrdiff_t(s), recs.begin() + std::ptrdiff_t(e), exact_order);
    for (std::size_t k = s + 1; k < e; ++k) {
      const VertexId a(recs[k - 1].v), b(recs[k].v);
      if (!(m.point(a) == m.point(b))) continue;  // a hash collision, or another group
      const std::pair<std::uint32_t, std::uint32_t> ids{m.input_vertex(a), m.input_vertex(b)};
      if (!first || ids < *first) std::tie(first, fa, fb) = std::tuple(ids, a, b);
    }
  }
  if (first) throw_coincident(m, fa, fb);
}

std::vector<BoundaryFace> boundary_faces(const ClassifiedTetMesh& m) {
  std::vector<BoundaryFace> out;
  for (std::size_t t = 0; t < m.num_tets(); ++t)
    for (int i = 0; i < 4; ++i)
      if (!m.tet_neighbor(TetId(t), i).valid()) {
        const auto& tv = m.tet(TetId(t));
        out.push_back({{tv[kTetFace[i][0]], tv[kTetFace[i][1]], tv[kTetFace[i][2]]}, TetId(t), i});
      }
  return out;
}

[[noreturn, gnu::cold]] void throw_crossing(const ClassifiedTetMesh& m, const BoundaryFace& f, const BoundaryFace& g) {
  auto tri = [&](const BoundaryFace& x) {
    return "(" + vertex_number(m, x.v[0]) + ", " + vertex_number(m, x.v[1]) + ", " + vertex_number(m, x.v[2]) + ")";
  };
  const TetId first = m.input_tet(f.t) <= m.input_tet(g.t) ? f.t : g.t;
  throw InputError(m.source(), "tet " + tet_number(m, first),
                   "the boundary triangle " + tri(f) + " of tet " + tet_number(m, f.t) + " and the boundary triangle " +
                       tri(g) + " of tet " + tet_number(m, g.t) +
                       " meet away from the vertices and edge they share: the mesh overlaps itself or holds a crack "
                       "(tets that touch must share their vertices and triangles)");
}

// The first crossing pair (smallest indices) among pairs offered to it.
struct FirstCrossing {
  const ClassifiedTetMesh& m;
  const std::vector<BoundaryFace>& faces;
  std::optional<FacePair> found;
  std::size_t tested = 0;
  void offer(std::uint32_t i, std::uint32_t j) {
    if (i > j) std::swap(i, j);
    ++tested;
    if ((!found || FacePair{i, j} < *found) && triangles_cross(faces[i].v, faces[j].v, m.points()))
      found = FacePair{i, j};
  }
  void throw_if_found() const {
    if (found) throw_crossing(m, faces[found->first], faces[found->second]);
  }
};

int shared_vertices(const BoundaryFace& f, const BoundaryFace& g) {
  int n = 0;
  for (VertexId v : f.v) n += int(v == g.v[0]) + int(v == g.v[1]) + int(v == g.v[2]);
  return n;
}

// ---- 2a. Pairs sharing an edge: the boundary faces sorted by edge id.
struct EdgeRec { std::uint32_t edge, face; };

std::vector<EdgeRec> faces_by_edge(const ClassifiedTetMesh& m, const std::vector<BoundaryFace>& faces) {
  std::vector<EdgeRec> recs;
  recs.reserve(3 * faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k)
    for (int e = 0; e < 6; ++e)
      if (kTetEdge[e][0] != faces[k].i && kTetEdge[e][1] != faces[k].i)
        recs.push_back({m.tet_edge(faces[k].t, e).idx, std::uint32_t(k)});
  radix_sort_by_key(recs, [](const EdgeRec& r) { return std::uint64_t(r.edge); },
                    std::max(1, int(std::bit_width(m.num_edges()))));
  return recs;
}

// Calls f(s, e) for each run [s, e) of records with one edge.
template <class F>
void for_each_edge_run(const std::vector<EdgeRec>& recs, F&& f) {
  for (std::size_t s = 0, e = 0; s < recs.size(); s = e) {
    for (e = s + 1; e < recs.size() && recs[e].edge == recs[s].edge;) ++e;
    f(s, e);
  }
}

void test_edge_pairs(const std::vector<EdgeRec>& recs, FirstCrossing& fc) {
  for_each_edge_run(recs, [&](std::size_t s, std::size_t e) {
    for (std::size_t i = s; i < e; ++i)
      for (std::size_t j = i + 1; j < e; ++j) fc.offer(recs[i].face, recs[j].face);
  });
}

// ---- 2b. Pairs sharing one vertex only (those sharing two share an edge).
void test_vertex_pairs(const ClassifiedTetMesh& m, const std::vector<BoundaryFace>& faces, FirstCrossing& fc) {
  std::vector<std::uint32_t> off(m.num_vertices() + 1, 0), list(3 * faces.size());
  for (const BoundaryFace& f : faces)
    for (VertexId v : f.v) ++off[v.idx + 1];
  std::partial_sum(off.begin(), off.end(), off.begin());
  {
    std::vector<std::uint32_t> fill(off.begin(), off.end() - 1);
    for (std::size_t k = 0; k < faces.size(); ++k)
      for (VertexId v : faces[k].v) list[fill[v.idx]++] = std::uint32_t(k);
  }
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    for (std::uint32_t i = off[v]; i < off[v + 1]; ++i)
      for (std::uint32_t j = i + 1; j < off[v + 1]; ++j)
        if (shared_vertices(faces[list[i]], faces[list[j]]) == 1) fc.offer(list[i], list[j]);
}

// ---- 2c. Pairs sharing no vertex whose boxes meet.
struct Box3 {
  Point3 lo, hi;
  bool meets(const Box3& o) const {
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z && o.lo.z <= hi.z;
  }
};
template <std::size_t N>
Box3 box_of(const ClassifiedTetMesh& m, const std::array<VertexId, N>& v) {
  Box3 b{m.point(v[0]), m.point(v[0])};
  for (std::size_t k = 1; k < N; ++k) {
    const Point3& p = m.point(v[k]);
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
  }
  return b;
}

// Integer cells of side h from `lo`: monotone in each coordinate (a
// subtraction and a multiplication by constants, a floor and a clamp), so a
// point of two boxes lies in a cell of both boxes' cell ranges.
struct CellMap {
  static constexpr double kMaxCell = double((1u << 21) - 1);
  Point3 lo;
  double inv = 1;
  Point3 top{kMaxCell, kMaxCell, kMaxCell};  // the largest cell per axis
  std::array<std::uint32_t, 3> cell(const Point3& p) const {
    std::array<std::uint32_t, 3> c;
    for (int d = 0; d < 3; ++d) c[d] = std::uint32_t(std::clamp(std::floor((p[d] - lo[d]) * inv), 0.0, top[d]));
    return c;
  }
  // Cells beyond cell(hi) are clamped to it (still monotone); keys pack
  // them in as few bits as they need (fewer radix passes).
  int shift1 = 21, shift2 = 42, bits = 63;
  void fit(const Point3& hi) {
    const auto c = cell(hi);
    top = {double(c[0]), double(c[1]), double(c[2])};
    shift1 = std::max(1, int(std::bit_width(c[0])));
    shift2 = shift1 + std::max(1, int(std::bit_width(c[1])));
    bits = shift2 + std::max(1, int(std::bit_width(c[2])));
  }
  std::uint64_t key(const std::array<std::uint32_t, 3>& c) const {
    return std::uint64_t(c[0]) | std::uint64_t(c[1]) << shift1 | std::uint64_t(c[2]) << shift2;
  }
};

// Calls f(key) for every cell of the box b.
template <class F>
void for_each_cell(const CellMap& cm, const Box3& b, F&& f) {
  const auto lo = cm.cell(b.lo), hi = cm.cell(b.hi);
  for (std::uint32_t z = lo[2]; z <= hi[2]; ++z)
    for (std::uint32_t y = lo[1]; y <= hi[1]; ++y)
      for (std::uint32_t x = lo[0]; x <= hi[0]; ++x) f(cm.key({x, y, z}));
}

CellMap cells_for(const std::vector<Box3>& boxes) {
  CellMap cm;
  cm.lo = boxes[0].lo;
  Point3 hi = boxes[0].hi;
  double sum = 0;
  for (const Box3& b : boxes) {
    cm.lo = {std::min(cm.lo.x, b.lo.x), std::min(cm.lo.y, b.lo.y), std::min(cm.lo.z, b.lo.z)};
    hi = {std::max(hi.x, b.hi.x), std::max(hi.y, b.hi.y), std::max(hi.z, b.hi.z)};
    sum += std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z});
  }
  const double h = sum / double(boxes.size());  // the mean box size: a few faces per cell
  cm.inv = h > 0 && std::isfinite(1.0 / h) ? 1.0 / h : 1.0;
  cm.fit(hi);
  return cm;
}

// The grid: each face in every cell its box covers, pairs tested in the
// cell of the larger lower corner of their boxes (once each). Returns false,
// having tested nothing, when the cells or pairs would exceed a budget
// linear in the number of faces (boxes of very different sizes).
bool test_disjoint_pairs_grid(const std::vector<BoundaryFace>& faces, const std::vector<Box3>& boxes,
                              FirstCrossing& fc) {
  const CellMap cm = cells_for(boxes);
  const std::uint64_t budget = 8 * std::uint64_t(faces.size()) + 1024;
  struct Rec { std::uint64_t key; std::uint32_t face; };
  std::vector<Rec> recs;
  std::vector<std::uint64_t> lo_key(faces.size());  // the cells of the boxes' lower corners
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const auto lo = cm.cell(boxes[k].lo), hi = cm.cell(boxes[k].hi);
    lo_key[k] = cm.key(lo);
    if (std::uint64_t(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1) + recs.size() > budget) return false;
    for_each_cell(cm, boxes[k], [&](std::uint64_t key) { recs.push_back({key, std::uint32_t(k)}); });
  }
  radix_sort_by_key(recs, [](const Rec& r) { return r.key; }, cm.bits);
  std::uint64_t pairs = 0;
  for (std::size_t s = 0, e = 0; s < recs.size(); s = e) {
    for (e = s + 1; e < recs.size() && recs[e].key == recs[s].key;) ++e;
    pairs += std::uint64_t(e - s) * (e - s - 1) / 2;
  }
  if (pairs > 4 * budget) return false;
  // The larger lower corner's cell, axis by axis, from the packed keys.
  const std::uint64_t mask[3] = {(std::uint64_t(1) << cm.shift1) - 1,
                                 ((std::uint64_t(1) << cm.shift2) - 1) ^ ((std::uint64_t(1) << cm.shift1) - 1),
                                 ((std::uint64_t(1) << cm.bits) - 1) ^ ((std::uint64_t(1) << cm.shift2) - 1)};
  auto max_cell = [&](std::uint64_t a, std::uint64_t b) {
    return std::max(a & mask[0], b & mask[0]) | std::max(a & mask[1], b & mask[1]) | std::max(a & mask[2], b & mask[2]);
  };
  for (std::size_t s = 0, e = 0; s < recs.size(); s = e) {
    for (e = s + 1; e < recs.size() && recs[e].key == recs[s].key;) ++e;
    for (std::size_t i = s; i < e; ++i)
      for (std::size_t j = i + 1; j < e; ++j) {
        const std::uint32_t a = recs[i].face, b = recs[j].face;
        if (max_cell(lo_key[a], lo_key[b]) == recs[s].key && boxes[a].meets(boxes[b]) &&
            shared_vertices(faces[a], faces[b]) == 0)
          fc.offer(a, b);
      }
  }
  return true;
}

// The same pairs from CGAL's box intersection (any box sizes, O(n log^3 n)).
void test_disjoint_pairs_boxes(const std::vector<BoundaryFace>& faces, const std::vector<Box3>& boxes,
                               FirstCrossing& fc) {
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const BoundaryFace*>;
  std::vector<Box> cgal_boxes;
  cgal_boxes.reserve(faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k)
    cgal_boxes.emplace_back(CGAL::Bbox_3(boxes[k].lo.x, boxes[k].lo.y, boxes[k].lo.z, boxes[k].hi.x, boxes[k].hi.y,
                                         boxes[k].hi.z),
                            &faces[k]);
  CGAL::box_self_intersection_d(cgal_boxes.begin(), cgal_boxes.end(), [&](const Box& x, const Box& y) {
    if (shared_vertices(*x.handle(), *y.handle()) == 0)
      fc.offer(std::uint32_t(x.handle() - faces.data()), std::uint32_t(y.handle() - faces.data()));
  });
}

void check_boundary_embedded(const ClassifiedTetMesh& m, const std::vector<BoundaryFace>& faces,
                             const std::vector<EdgeRec>& by_edge, SelfOverlapStats& st) {
  if (faces.empty()) return;  // never for a finite mesh; the grid needs one box
  FirstCrossing fc{m, faces, std::nullopt, 0};
  test_edge_pairs(by_edge, fc);
  test_vertex_pairs(m, faces, fc);
  std::vector<Box3> boxes(faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k) boxes[k] = box_of(m, faces[k].v);
  if (!test_disjoint_pairs_grid(faces, boxes, fc)) test_disjoint_pairs_boxes(faces, boxes, fc);
  st.tested_pairs = fc.tested;
  fc.throw_if_found();
}

// ---- 3. No part inside another.

// The pieces of the boundary: faces joined across edges that have exactly two
// boundary faces. Returns one face of each (its smallest index).
std::vector<std::uint32_t> piece_representatives(std::size_t num_faces, const std::vector<EdgeRec>& by_edge) {
  UnionFind pieces(num_faces);
  for_each_edge_run(by_edge, [&](std::size_t s, std::size_t e) {
    if (e - s == 2) pieces.unite(by_edge[s].face, by_edge[s + 1].face);
  });
  std::vector<std::uint32_t> reps;
  for (std::size_t k = 0; k < num_faces; ++k)
    if (pieces.find(k) == k) reps.push_back(std::uint32_t(k));
  return reps;
}

// EXACT: whether the closed tet t holds the centroid of face f (each face of
// t in kTetFace order has its right-hand normal outwards: Positive = outside).
bool tet_holds_centroid(const ClassifiedTetMesh& m, TetId t, const BoundaryFace& f) {
  const auto& tv = m.tet(t);
  const Point3 &p = m.point(f.v[0]), &q = m.point(f.v[1]), &r = m.point(f.v[2]);
  for (int i = 0; i < 4; ++i)
    if (orient3d_centroid(m.point(tv[kTetFace[i][0]]), m.point(tv[kTetFace[i][1]]), m.point(tv[kTetFace[i][2]]), p, q,
                          r) == Sign::Positive)
      return false;
  return true;
}

[[noreturn, gnu::cold]] void throw_nested(const ClassifiedTetMesh& m, TetId t, const BoundaryFace& f) {
  throw InputError(m.source(), "tet " + tet_number(m, t),
                   "tets " + tet_number(m, t) + " and " + tet_number(m, f.t) + " overlap: tet " + tet_number(m, t) +
                       " holds the centroid of the boundary triangle (" + vertex_number(m, f.v[0]) + ", " +
                       vertex_number(m, f.v[1]) + ", " + vertex_number(m, f.v[2]) + ") of tet " + tet_number(m, f.t) +
                       ": a part of the mesh lies inside another (the mesh covers that place twice)");
}

// The cells of a grid over the pieces' sample faces (about one cell per
// piece), each with the pieces whose face box covers it.
struct PieceCells {
  CellMap cm;
  Box3 all;                // the faces' boxes' union
  std::vector<Box3> boxes;  // per piece, its sample face's box
  struct Rec { std::uint64_t key; std::uint32_t piece; };
  std::vector<Rec> recs;    // sorted by key

  explicit PieceCells(std::vector<Box3> b) : boxes(std::move(b)) {
    all = boxes[0];
    for (const Box3& x : boxes)
      all = {{std::min(all.lo.x, x.lo.x), std::min(all.lo.y, x.lo.y), std::min(all.lo.z, x.lo.z)},
             {std::max(all.hi.x, x.hi.x), std::max(all.hi.y, x.hi.y), std::max(all.hi.z, x.hi.z)}};
    const double ext = std::max({all.hi.x - all.lo.x, all.hi.y - all.lo.y, all.hi.z - all.lo.z});
    const double n = std::ceil(std::cbrt(double(boxes.size())));
    cm.lo = all.lo;
    cm.inv = ext > 0 && std::isfinite(n / ext) ? n / ext : 1.0;
    cm.fit(all.hi);
    for (std::size_t q = 0; q < boxes.size(); ++q)
      for_each_cell(cm, boxes[q], [&](std::uint64_t key) { recs.push_back({key, std::uint32_t(q)}); });
    radix_sort_by_key(recs, [](const Rec& r) { return r.key; }, cm.bits);
  }
  // Calls f(piece) once for each piece whose box meets b (in the cell of the
  // larger lower corner of the two boxes).
  template <class F>
  void for_each_meeting(const Box3& b, F&& f) const {
    if (!b.meets(all)) return;
    const auto lo = cm.cell(b.lo);
    for_each_cell(cm, b, [&](std::uint64_t key) {
      auto it = std::lower_bound(recs.begin(), recs.end(), key, [](const Rec& r, std::uint64_t k) { return r.key < k; });
      for (; it != recs.end() && it->key == key; ++it) {
        const auto ql = cm.cell(boxes[it->piece].lo);
        if (cm.key({std::max(lo[0], ql[0]), std::max(lo[1], ql[1]), std::max(lo[2], ql[2])}) == key &&
            boxes[it->piece].meets(b))
          f(it->piece);
      }
    });
  }
};

// One centroid per piece against every tet. With one piece there is nothing
// to test: its outer side is the unbounded region's (L15, step 3).
void check_no_nesting(const ClassifiedTetMesh& m, const std::vector<BoundaryFace>& faces,
                      const std::vector<EdgeRec>& by_edge, SelfOverlapStats& st) {
  const std::vector<std::uint32_t> reps = piece_representatives(faces.size(), by_edge);
  st.pieces = reps.size();
  if (reps.size() < 2) return;
  std::vector<Box3> boxes;
  for (std::uint32_t k : reps) boxes.push_back(box_of(m, faces[k].v));
  const PieceCells cells(std::move(boxes));
  // Tets in id order, pieces in index order: the same report every run.
  for (std::size_t t = 0; t < m.num_tets(); ++t)
    cells.for_each_meeting(box_of(m, m.tet(TetId(t))), [&](std::uint32_t q) {
      const BoundaryFace& f = faces[reps[q]];
      if (f.t != TetId(t) && tet_holds_centroid(m, TetId(t), f)) throw_nested(m, TetId(t), f);
    });
}

}  // namespace

void check_self_overlap(const ClassifiedTetMesh& m, SelfOverlapStats* stats) {
  SelfOverlapStats local;
  SelfOverlapStats& st = stats ? *stats : local;
  auto t0 = Clock::now();
  check_coincident_vertices(m);
  st.seconds_vertices = since(t0);
  t0 = Clock::now();
  const std::vector<BoundaryFace> faces = boundary_faces(m);
  st.boundary_triangles = faces.size();
  const std::vector<EdgeRec> by_edge = faces_by_edge(m, faces);
  check_boundary_embedded(m, faces, by_edge, st);
  st.seconds_boundary = since(t0);
  t0 = Clock::now();
  check_no_nesting(m, faces, by_edge, st);
  st.seconds_nesting = since(t0);
}

}  // namespace polydual
