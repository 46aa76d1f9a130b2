#include "optim/boundary.h"

#include <set>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace polydual {

Point3 closest_point_on_segment(const Point3& x, const Point3& a, const Point3& b) {
  const Vec3 ab = b - a;
  const double l2 = norm2(ab);
  if (!(l2 > 0)) return a;
  const double t = std::clamp(dot(x - a, ab) / l2, 0.0, 1.0);
  return a + t * ab;
}

Point3 closest_point_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + (vb * denom) * ab + (vc * denom) * ac;
}

Point3 BoundaryConstraints::closest(std::uint32_t i, const Point3& x) const {
  const Prim& q = prims_[i];
  if (q.dim == 1) return closest_point_on_segment(x, verts_[q.v[0].idx], verts_[q.v[1].idx]);
  return closest_point_on_triangle(x, verts_[q.v[0].idx], verts_[q.v[1].idx], verts_[q.v[2].idx]);
}

BoundaryConstraints::BoundaryConstraints(const ModelFacets& facets, const PolyMesh& mesh, bool lazy, bool keep)
    : verts_(facets.points), cls_(mesh.point_class), mesh_(&mesh), lazy_(lazy), keep_(keep) {
  collect_primitives(facets);
  if (keep_) collect_face_edges(facets);
  index_vertex_primitives();
  build_grid();
  assign_initial_primitives();
}

// The facetisation: triangles on model faces, then edges on model edges.
void BoundaryConstraints::collect_primitives(const ModelFacets& facets) {
  for (const ModelFacet& t : facets.triangles) prims_.push_back({t.v, 2, t.tag, t.src});
  num_tri_prims_ = static_cast<std::uint32_t>(prims_.size());
  for (const ModelFacet& s : facets.segments) prims_.push_back({s.v, 1, s.tag, s.src});
}

// Segments of the edges inside model faces, after the model edges': the
// segment primitives stay sorted by EdgeId within each kind, and own_primitive
// looks an edge up in both.
void BoundaryConstraints::collect_face_edges(const ModelFacets& facets) {
  for (const ModelFacet& s : facets.face_edges) prims_.push_back({s.v, 1, kFaceEdgeTag, s.src});
}

std::uint32_t BoundaryConstraints::own_primitive(std::size_t p) const {
  if (mesh_->point_origin.size() != mesh_->num_points()) return kNone;
  const PointOrigin o = mesh_->point_origin[p];
  if (o.dim != 1 && o.dim != 2) return kNone;
  auto find = [&](auto first, auto last) -> std::uint32_t {
    const auto it = std::lower_bound(first, last, o.id, [](const Prim& q, std::uint32_t id) { return q.src < id; });
    return it != last && it->src == o.id && it->dim == o.dim ? static_cast<std::uint32_t>(it - prims_.begin()) : kNone;
  };
  if (o.dim == 2) return find(prims_.begin(), prims_.begin() + num_tri_prims_);
  // Model-edge segments, then face-edge segments: each run sorted by EdgeId.
  const auto seg = prims_.begin() + num_tri_prims_;
  const auto split = std::partition_point(seg, prims_.end(), [](const Prim& q) { return q.tag != kFaceEdgeTag; });
  const std::uint32_t a = find(seg, split);
  return a != kNone ? a : find(split, prims_.end());
}

// Vertex -> primitives (CSR, primitives increasing per vertex: deterministic walks).
void BoundaryConstraints::index_vertex_primitives() {
  vprim_off_.assign(verts_.size() + 1, 0);
  for (const Prim& q : prims_)
    for (int k = 0; k < q.dim + 1; ++k) ++vprim_off_[q.v[k].idx + 1];
  for (std::size_t v = 0; v < verts_.size(); ++v) vprim_off_[v + 1] += vprim_off_[v];
  vprim_.resize(vprim_off_.back());
  std::vector<std::uint32_t> fill(vprim_off_.begin(), vprim_off_.end() - 1);
  for (std::uint32_t i = 0; i < prims_.size(); ++i)
    for (int k = 0; k < prims_[i].dim + 1; ++k) vprim_[fill[prims_[i].v[k].idx]++] = i;
}

// Uniform grid over the primitives' bounding boxes: cell size kGridCellExtents
// x the mean primitive extent, at most kMaxGridCells cells along the longest
// axis; each primitive is listed in every cell its box meets.
void BoundaryConstraints::build_grid() {
  Point3 hi{-kFar, -kFar, -kFar};
  lo_ = {kFar, kFar, kFar};
  double ext = 0;
  box_.resize(prims_.size());
  for (std::size_t i = 0; i < prims_.size(); ++i) {
    const Prim& q = prims_[i];
    Point3 a = verts_[q.v[0].idx], b = a;
    for (int k = 1; k < q.dim + 1; ++k)
      for (int d = 0; d < 3; ++d) {
        a[d] = std::min(a[d], verts_[q.v[k].idx][d]);
        b[d] = std::max(b[d], verts_[q.v[k].idx][d]);
      }
    box_[i] = {a, b};
    for (int d = 0; d < 3; ++d) { lo_[d] = std::min(lo_[d], a[d]); hi[d] = std::max(hi[d], b[d]); }
    ext += std::max({b.x - a.x, b.y - a.y, b.z - a.z});
  }
  // The computed distances carry rounding of a few ulps of the coordinates;
  // a box is skipped only when it is farther than the best by far more.
  double scale = 0;
  for (int d = 0; d < 3 && !prims_.empty(); ++d) scale = std::max({scale, std::fabs(lo_[d]), std::fabs(hi[d])});
  box_slack_ = 1e-10 * scale;
  if (!prims_.empty()) {
    h_ = std::max(kGridCellExtents * ext / static_cast<double>(prims_.size()), kMinGridCell);
    const double span = std::max({hi.x - lo_.x, hi.y - lo_.y, hi.z - lo_.z});
    h_ = std::max(h_, span / kMaxGridCells);
    for (int d = 0; d < 3; ++d) n_[d] = std::max(1, static_cast<int>(std::ceil((hi[d] - lo_[d]) / h_)) + 1);
  }
  auto cell_of = [&](double v, int d) { return std::clamp(static_cast<int>(std::floor((v - lo_[d]) / h_)), 0, n_[d] - 1); };
  const std::size_t ncell = static_cast<std::size_t>(n_[0]) * n_[1] * n_[2];
  std::vector<std::array<int, 6>> box(prims_.size());
  grid_off_.assign(ncell + 1, 0);
  // Pass 0 counts the entries of each cell (and computes the boxes), pass 1 fills them.
  for (std::uint32_t pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> fill;
    if (pass == 1) {
      for (std::size_t i = 0; i < ncell; ++i) grid_off_[i + 1] += grid_off_[i];
      grid_.resize(grid_off_.back());
      fill.assign(grid_off_.begin(), grid_off_.end() - 1);
    }
    for (std::uint32_t i = 0; i < prims_.size(); ++i) {
      auto& bx = box[i];
      if (pass == 0) {
        const Prim& q = prims_[i];
        for (int d = 0; d < 3; ++d) { bx[d] = n_[d]; bx[d + 3] = -1; }
        for (int k = 0; k < q.dim + 1; ++k)
          for (int d = 0; d < 3; ++d) {
            const int c = cell_of(verts_[q.v[k].idx][d], d);
            bx[d] = std::min(bx[d], c);
            bx[d + 3] = std::max(bx[d + 3], c);
          }
      }
      for (int x = bx[0]; x <= bx[3]; ++x)
        for (int y = bx[1]; y <= bx[4]; ++y)
          for (int z = bx[2]; z <= bx[5]; ++z) {
            const std::size_t c = (static_cast<std::size_t>(x) * n_[1] + y) * n_[2] + z;
            if (pass == 0) ++grid_off_[c + 1];
            else grid_[fill[c]++] = i;
          }
    }
  }
}

// Initial primitive of every boundary point: the nearest of its model entity
// (parallel over the points: each search reads the grid only). A point of an
// entity without primitives stays fixed. Lazy: only the degrees of freedom
// now, each search at the point's first ensure().
void BoundaryConstraints::assign_initial_primitives() {
  const std::size_t np = mesh_->num_points();
  std::set<std::pair<int, std::int32_t>> entities;  // (dim, tag) with a primitive
  for (const Prim& q : prims_) entities.insert({q.dim, q.tag});
  dof_.assign(np, 0);
  current_.assign(np, kNone);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 2048), [&](const auto& rg) {
    for (std::size_t p = rg.begin(); p != rg.end(); ++p) {
      const ModelRef r = cls_[p];
      if (r.dim == 3) dof_[p] = 3;
      if ((r.dim != 1 && r.dim != 2) || !entities.count({r.dim, r.tag}) || !is_finite(mesh_->points[p])) continue;
      if (keep_) {  // the dimension of its own primitive; a vertex's point (none) stays fixed
        const std::uint32_t own = own_primitive(p);
        dof_[p] = own == kNone ? 0 : static_cast<std::uint8_t>(prims_[own].dim);
        if (own != kNone && !lazy_) current_[p] = own;
        continue;
      }
      dof_[p] = static_cast<std::uint8_t>(r.dim);
      if (!lazy_) assign_initial(p);
    }
  });
}

void BoundaryConstraints::assign_initial(std::size_t p) {
  if (keep_) {
    current_[p] = own_primitive(p);
    return;
  }
  const ModelRef r = cls_[p];
  const bool origins = mesh_->point_origin.size() == mesh_->num_points();
  const std::uint32_t seed = origins ? origin_primitive(mesh_->point_origin[p], r) : kNone;
  current_[p] = nearest_by_grid(mesh_->points[p], r.dim, r.tag, seed);
}

std::uint32_t BoundaryConstraints::origin_primitive(const PointOrigin& o, const ModelRef& r) const {
  auto of_entity = [&](std::uint32_t q) { return prims_[q].dim == r.dim && prims_[q].tag == r.tag; };
  if (o.dim == 0) {
    if (o.id >= verts_.size()) return kNone;
    for (std::uint32_t a = vprim_off_[o.id]; a < vprim_off_[o.id + 1]; ++a)
      if (of_entity(vprim_[a])) return vprim_[a];
    return kNone;
  }
  if (o.dim != 1 && o.dim != 2) return kNone;
  const auto first = prims_.begin() + (o.dim == 2 ? 0 : num_tri_prims_);
  const auto last = o.dim == 2 ? prims_.begin() + num_tri_prims_ : prims_.end();
  const auto it = std::lower_bound(first, last, o.id, [](const Prim& q, std::uint32_t id) { return q.src < id; });
  if (it == last || it->src != o.id) return kNone;
  const auto q = static_cast<std::uint32_t>(it - prims_.begin());
  return of_entity(q) ? q : kNone;
}

// The nearest primitive of the entity, ties to the lowest index, among the
// grid's rings out to where no nearer one can lie. A primitive whose box is
// farther than the best found by more than the rounding slack cannot be
// nearer or tie, so its closest point is not computed; the seed, tried
// first, makes that skip the rule.
std::uint32_t BoundaryConstraints::nearest_by_grid(const Point3& x, int dim, std::int32_t tag,
                                                   std::uint32_t seed) const {
  if (prims_.empty()) return kNone;
  auto box_distance = [&](std::uint32_t q) {
    double s2 = 0;
    for (int d = 0; d < 3; ++d) {
      const double o = std::max({box_[q][0][d] - x[d], x[d] - box_[q][1][d], 0.0});
      s2 += o * o;
    }
    return std::sqrt(s2);
  };
  int c[3];
  double outside = 0;  // distance from x to the grid box
  for (int d = 0; d < 3; ++d) {
    const double t = (x[d] - lo_[d]) / h_;
    c[d] = std::clamp(static_cast<int>(std::floor(t)), 0, n_[d] - 1);
    const double over = std::max(lo_[d] - x[d], x[d] - (lo_[d] + n_[d] * h_));
    outside = std::max(outside, over);
  }
  std::uint32_t best = kNone;
  double bestd = std::numeric_limits<double>::infinity();
  if (seed != kNone) { best = seed; bestd = norm(closest(seed, x) - x); }
  const int rmax = std::max({n_[0], n_[1], n_[2]});
  for (int r = 0; r <= rmax; ++r) {
    for (int i = c[0] - r; i <= c[0] + r; ++i)
      for (int j = c[1] - r; j <= c[1] + r; ++j)
        for (int k = c[2] - r; k <= c[2] + r; ++k) {
          if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) != r) continue;
          if (i < 0 || j < 0 || k < 0 || i >= n_[0] || j >= n_[1] || k >= n_[2]) continue;
          const std::size_t g = (static_cast<std::size_t>(i) * n_[1] + j) * n_[2] + k;
          for (std::uint32_t a = grid_off_[g]; a < grid_off_[g + 1]; ++a) {
            const std::uint32_t q = grid_[a];
            if (prims_[q].dim != dim || prims_[q].tag != tag || q == best) continue;
            if (box_distance(q) > bestd + box_slack_) continue;
            const double d = norm(closest(q, x) - x);
            if (d < bestd || (d == bestd && q < best)) { bestd = d; best = q; }
          }
        }
    // Cells of ring r+1 are at least r*h_ away from x's cell (minus the offset outside).
    if (best != kNone && bestd <= r * h_ - outside) break;
  }
  return best;
}

void BoundaryConstraints::tangent_basis(PointId p, Vec3 basis[3]) const {
  const int k = dof_[p.idx];
  if (k == 3) {
    basis[0] = {1, 0, 0}; basis[1] = {0, 1, 0}; basis[2] = {0, 0, 1};
    return;
  }
  if (k == 0) return;
  const Prim& q = prims_[current_[p.idx]];
  const Point3 &a = verts_[q.v[0].idx], &b = verts_[q.v[1].idx];
  basis[0] = (b - a) / norm(b - a);
  if (k == 2) {
    const Vec3 n = cross(b - a, verts_[q.v[2].idx] - a);
    const Vec3 t2 = cross(n, basis[0]);
    basis[1] = t2 / norm(t2);
  }
}

Point3 BoundaryConstraints::project(PointId p, const Point3& x, std::uint32_t* prim,
                                    std::uint32_t start) const {
  const int k = dof_[p.idx];
  if (k != 1 && k != 2) {
    if (prim) *prim = kNone;
    return x;
  }
  std::uint32_t cur = start == kNone ? current_[p.idx] : start;
  const Prim& me = prims_[cur];
  Point3 y = closest(cur, x);
  if (keep_) {  // its own triangle or edge only
    if (prim) *prim = cur;
    return y;
  }
  double dy = norm2(y - x);
  for (int hop = 0; hop < kMaxHops; ++hop) {
    std::uint32_t next = cur;
    const Prim& pc = prims_[cur];
    for (int v = 0; v < pc.dim + 1; ++v) {
      const VertexId pv = pc.v[v];
      for (std::uint32_t a = vprim_off_[pv.idx]; a < vprim_off_[pv.idx + 1]; ++a) {
        const std::uint32_t q = vprim_[a];
        if (q == cur || prims_[q].dim != me.dim || prims_[q].tag != me.tag) continue;
        const Point3 z = closest(q, x);
        const double dz = norm2(z - x);
        if (dz < dy) { dy = dz; y = z; next = q; }
      }
    }
    if (next == cur) break;
    cur = next;
  }
  if (prim) *prim = cur;
  return y;
}

double BoundaryConstraints::distance_to_entity(PointId p, const Point3& x) const {
  const ModelRef r = cls_[p.idx];
  double best = std::numeric_limits<double>::infinity();
  for (std::uint32_t q = 0; q < prims_.size(); ++q)
    if (prims_[q].dim == r.dim && prims_[q].tag == r.tag) best = std::min(best, norm(closest(q, x) - x));
  return best;
}

}  // namespace polydual
