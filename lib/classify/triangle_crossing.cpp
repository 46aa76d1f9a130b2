// Each case decides with exact predicates (lib/predicates): orient3d,
// orient2d inside a coordinate plane, CGAL's filtered coplanar_orientation
// and do_intersect. Why each case suffices: proofs/self_overlap.md L15, step 2.
#include "classify/triangle_crossing.h"

#include <initializer_list>

#include "predicates/predicates.h"

namespace polydual {

namespace {

// Fast paths: points that all have the same coordinate k lie in the plane
// x_k = const, where orient2d on the other two coordinates decides every
// in-plane sign exactly (the flat walls of box domains); points strictly on
// one side of a triangle's plane.

int common_axis(std::initializer_list<const Point3*> pts) {
  for (int k = 0; k < 3; ++k) {
    bool same = true;
    for (const Point3* p : pts) same = same && (*p)[k] == (**pts.begin())[k];
    if (same) return k;
  }
  return -1;
}
Sign orient_in(int k, const Point3& a, const Point3& b, const Point3& c) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  return orient2d(a[i], a[j], b[i], b[j], c[i], c[j]);
}

// Triangles (a, b, c) and (a, b, d) sharing the edge ab: they meet beyond it
// iff they are coplanar with c and d on the same side of ab (otherwise their
// planes meet in the line ab, which each triangle meets in ab).
bool meet_beyond_edge(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const int k = common_axis({&a, &b, &c, &d});
  if (k >= 0) return orient_in(k, a, b, c) == orient_in(k, a, b, d);
  return orient3d(a, b, c, d) == Sign::Zero && coplanar_orientation(a, b, c, d) == Sign::Positive;
}

// In the plane x_k = const: whether the closed angular sectors at a spanned
// by (b, c) and by (d, e) share more than a. Two convex sectors do iff a
// bounding ray of one lies in the other.
bool sectors_overlap(int k, const Point3& a, const Point3& b, const Point3& c, const Point3& d, const Point3& e) {
  // x is in the sector of (p, q), s = orient(a, p, q), iff it is on q's side
  // of the line ap (or on it) and on p's side of the line aq (or on it).
  auto in_sector = [&](const Point3& x, const Point3& p, const Point3& q, Sign s) {
    const Sign o1 = orient_in(k, a, p, x);
    if (o1 != Sign::Zero && o1 != s) return false;
    const Sign o2 = orient_in(k, a, q, x);
    return o2 == Sign::Zero || o2 == Sign(-int(s));
  };
  const Sign sf = orient_in(k, a, b, c), sg = orient_in(k, a, d, e);
  return in_sector(d, b, c, sf) || in_sector(e, b, c, sf) || in_sector(b, d, e, sg) || in_sector(c, d, e, sg);
}

// Triangles (a, b, c) and (a, d, e) sharing only a: they meet beyond a iff
// [b, c] meets (a, d, e) or [d, e] meets (a, b, c).
bool meet_beyond_vertex(const Point3& a, const Point3& b, const Point3& c, const Point3& d, const Point3& e) {
  const int k = common_axis({&a, &b, &c, &d, &e});
  if (k >= 0) return sectors_overlap(k, a, b, c, d, e);
  const Sign sd = orient3d(a, b, c, d), se = orient3d(a, b, c, e);
  if (sd != Sign::Zero && sd == se) return false;  // (a, d, e) meets the plane of (a, b, c) in a only
  const Sign sb = orient3d(a, d, e, b), sc = orient3d(a, d, e, c);
  if (sb != Sign::Zero && sb == sc) return false;
  return segment_meets_triangle(b, c, a, d, e) || segment_meets_triangle(d, e, a, b, c);
}

// In the plane x_k = const: closed triangles are disjoint iff the line of an
// edge of one has the other strictly on its outer side.
bool triangles_meet_in_plane(int k, const std::array<const Point3*, 3>& p, const std::array<const Point3*, 3>& q) {
  auto separates = [&](const std::array<const Point3*, 3>& t, const std::array<const Point3*, 3>& u) {
    const Sign inner = orient_in(k, *t[0], *t[1], *t[2]);
    for (int i = 0; i < 3; ++i) {
      bool all_out = true;
      for (int j = 0; j < 3 && all_out; ++j) all_out = orient_in(k, *t[i], *t[(i + 1) % 3], *u[j]) == Sign(-int(inner));
      if (all_out) return true;
    }
    return false;
  };
  return !separates(p, q) && !separates(q, p);
}

// Closed triangles with no vertex in common.
bool triangles_meet_anywhere(const std::array<const Point3*, 3>& p, const std::array<const Point3*, 3>& q) {
  auto one_side = [](const std::array<const Point3*, 3>& t, const std::array<const Point3*, 3>& u) {
    const Sign s0 = orient3d(*t[0], *t[1], *t[2], *u[0]);
    return s0 != Sign::Zero && orient3d(*t[0], *t[1], *t[2], *u[1]) == s0 && orient3d(*t[0], *t[1], *t[2], *u[2]) == s0;
  };
  const int k = common_axis({p[0], p[1], p[2], q[0], q[1], q[2]});
  if (k >= 0) return triangles_meet_in_plane(k, p, q);
  if (one_side(p, q) || one_side(q, p)) return false;
  return triangles_meet(*p[0], *p[1], *p[2], *q[0], *q[1], *q[2]);
}

}  // namespace

bool triangles_cross(const std::array<VertexId, 3>& f, const std::array<VertexId, 3>& g,
                     const std::vector<Point3>& points) {
  int in_g[3], shared = 0;  // in_g[k]: position of f[k] in g, or -1
  for (int k = 0; k < 3; ++k) {
    in_g[k] = -1;
    for (int l = 0; l < 3; ++l)
      if (f[k] == g[l]) in_g[k] = l;
    shared += in_g[k] >= 0;
  }
  const std::array<const Point3*, 3> P{&points[f[0].idx], &points[f[1].idx], &points[f[2].idx]};
  const std::array<const Point3*, 3> Q{&points[g[0].idx], &points[g[1].idx], &points[g[2].idx]};
  if (shared == 0) return triangles_meet_anywhere(P, Q);
  if (shared == 3) return true;  // the same triangle twice
  if (shared == 2) {
    const int c = in_g[0] < 0 ? 0 : (in_g[1] < 0 ? 1 : 2);  // f's vertex off the shared edge
    return meet_beyond_edge(*P[(c + 1) % 3], *P[(c + 2) % 3], *P[c], *Q[3 - in_g[(c + 1) % 3] - in_g[(c + 2) % 3]]);
  }
  const int k = in_g[0] >= 0 ? 0 : (in_g[1] >= 0 ? 1 : 2), l = in_g[k];
  return meet_beyond_vertex(*P[k], *P[(k + 1) % 3], *P[(k + 2) % 3], *Q[(l + 1) % 3], *Q[(l + 2) % 3]);
}

}  // namespace polydual
