#include "optim/foam_gate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace polydual {

namespace {

// The sine of the elevation of C below the triangle (t0, t1, t2), whose
// right-hand normal points out of the cell: positive when C is on the inner
// side, as OpenFOAM wants every decomposition tet of a cell. 0 for a
// degenerate triangle or C on t0 (OpenFOAM's quality is then 0: a failure).
double inner_sine(const Point3& t0, const Point3& t1, const Point3& t2, const Point3& C) {
  const Vec3 n = cross(t1 - t0, t2 - t0), d = C - t0;
  const double scale = norm(n) * norm(d);
  if (!(scale > 0)) return 0.0;
  return -dot(n, d) / scale;
}

// Calls fn(sine) for every decomposition tet OpenFOAM checks on loop `loop`
// (outward of its cell, face centre F) with the cell centre C: the centre fan
// about F, then the vertex fan from `base` (skipped if base is not on the loop).
template <class Fn>
void for_each_foam_tet(std::span<const PointId> loop, std::span<const Point3> pts, const Point3& F, PointId base,
                       const Point3& C, Fn&& fn) {
  const std::size_t k = loop.size();
  for (std::size_t i = 0; i < k; ++i) fn(inner_sine(pts[loop[i].idx], pts[loop[(i + 1) % k].idx], F, C));
  std::size_t b = k;
  for (std::size_t i = 0; i < k; ++i)
    if (loop[i] == base) b = i;
  if (b == k) return;
  const Point3& pb = pts[base.idx];
  for (std::size_t t = 1; t + 1 < k; ++t)
    fn(inner_sine(pb, pts[loop[(b + t) % k].idx], pts[loop[(b + t + 1) % k].idx], C));
}

// Cell c's face centres (one per loop, outward) into F and its OpenFOAM
// centre (primitiveMesh::makeCellCentresAndVols: pyramids about the mean of
// the face centres; that mean if the volume vanishes).
Point3 cell_centre_and_faces(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points,
                             std::vector<Point3>& F) {
  const std::uint32_t j0 = s.cell_loop_off[c], j1 = s.cell_loop_off[c + 1];
  thread_local std::vector<Vec3> A;
  F.resize(j1 - j0);
  A.resize(j1 - j0);
  Point3 est;
  for (std::uint32_t j = j0; j < j1; ++j) {
    F[j - j0] = foam_face_centre(s.loop(j), points, &A[j - j0]);
    est += F[j - j0];
  }
  est = est / static_cast<double>(j1 - j0);
  Point3 sum;
  double vol = 0;
  for (std::size_t i = 0; i < F.size(); ++i) {
    const double pyr3 = dot(A[i], F[i] - est);  // outward area: the owner's formula for both sides
    sum += pyr3 * (0.75 * F[i] + 0.25 * est);
    vol += pyr3;
  }
  return std::fabs(vol) > 1e-300 ? sum / vol : est;
}

// The worst sine of the vertex fan from loop point b with centre C (loop
// outward of C's cell).
double fan_min_sine(std::span<const PointId> loop, std::span<const Point3> pts, std::size_t b, const Point3& C) {
  const std::size_t k = loop.size();
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t t = 1; t + 1 < k; ++t)
    m = std::min(m, inner_sine(pts[loop[b].idx], pts[loop[(b + t) % k].idx], pts[loop[(b + t + 1) % k].idx], C));
  return m;
}

// The mesh face's loop as cell `side` sees it (outward), into out.
void outward_loop(const PolyMesh& mesh, std::uint32_t f, int side, std::vector<PointId>& out) {
  const auto loop = mesh.face(FaceId(f));
  out.assign(loop.begin(), loop.end());
  if (side == 1) std::reverse(out.begin(), out.end());
}

// Every cell's OpenFOAM centre (parallel; each entry depends on its cell only).
std::vector<Point3> foam_cell_centres(const MeshStencil& s, std::span<const Point3> points) {
  std::vector<Point3> C(s.num_cells());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, C.size(), 256), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) C[c] = foam_cell_centre(s, static_cast<std::uint32_t>(c), points);
  });
  return C;
}

}  // namespace

Point3 foam_face_centre(std::span<const PointId> loop, std::span<const Point3> points, Vec3* area) {
  const std::size_t k = loop.size();
  if (k == 3) {
    const Point3 &a = points[loop[0].idx], &b = points[loop[1].idx], &c = points[loop[2].idx];
    *area = 0.5 * cross(b - a, c - a);
    return (1.0 / 3.0) * (a + b + c);
  }
  Point3 avg;
  for (PointId q : loop) avg += points[q.idx];
  avg = avg / static_cast<double>(k);
  Vec3 sum_n, sum_ac;
  double sum_a = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const Point3 &p = points[loop[i].idx], &q = points[loop[(i + 1) % k].idx];
    const Vec3 n = cross(q - p, avg - p);
    const double a = norm(n);
    sum_n += n;
    sum_a += a;
    sum_ac += a * (p + q + avg);
  }
  if (sum_a < 1e-150) {  // OpenFOAM's ROOTVSMALL: a zero-area face
    *area = Vec3{};
    return avg;
  }
  *area = 0.5 * sum_n;
  return (1.0 / 3.0) * sum_ac / sum_a;
}

Point3 foam_cell_centre(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points) {
  thread_local std::vector<Point3> F;
  return cell_centre_and_faces(s, c, points, F);
}

std::vector<std::uint32_t> stencil_loop_faces(const PolyMesh& mesh, const MeshStencil& s) {
  std::vector<std::uint32_t> out(s.cell_loop_off.back());
  for (std::uint32_t c = 0; c < s.num_cells(); ++c) {
    std::uint32_t j = s.cell_loop_off[c];
    for (HalfFace h : mesh.cell(CellId(c))) out[j++] = h.face().idx;
  }
  return out;
}

void choose_foam_bases(const PolyMesh& mesh, const MeshStencil& s, std::span<const Point3> points,
                       std::vector<PointId>& base) {
  const std::vector<Point3> C = foam_cell_centres(s, points);
  const bool fresh = base.size() != mesh.num_faces();
  if (fresh) base.assign(mesh.num_faces(), PointId());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, base.size(), 256), [&](const auto& r) {
    std::vector<PointId> own, nei;
    for (std::size_t f = r.begin(); f != r.end(); ++f) {
      outward_loop(mesh, static_cast<std::uint32_t>(f), 0, own);
      const CellId o = mesh.face_owner[f], n = mesh.face_neighbour[f];
      const bool inner = n.valid() && n != o;
      if (inner) outward_loop(mesh, static_cast<std::uint32_t>(f), 1, nei);
      double best = -std::numeric_limits<double>::infinity();
      PointId pick = own.empty() ? PointId() : own[0];
      for (std::size_t b = 0; b < own.size(); ++b) {
        double m = o.valid() ? fan_min_sine(own, points, b, C[o.idx]) : 0.0;
        if (inner) m = std::min(m, fan_min_sine(nei, points, own.size() - 1 - b, C[n.idx]));
        if (m > best) { best = m; pick = own[b]; }
        if (m > 2 * kFoamMargin) break;  // the first that passes with room, as OpenFOAM takes the first
      }
      if (fresh || best > 2 * kFoamMargin) base[f] = pick;
    }
  });
}

bool foam_cell_ok(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points,
                  std::span<const PointId> base, std::span<const std::uint32_t> loop_face, Point3* centre) {
  thread_local std::vector<Point3> F;
  const Point3 C = cell_centre_and_faces(s, c, points, F);
  if (centre) *centre = C;
  bool ok = true;
  const std::uint32_t j0 = s.cell_loop_off[c];
  for (std::uint32_t j = j0; j < s.cell_loop_off[c + 1] && ok; ++j)
    for_each_foam_tet(s.loop(j), points, F[j - j0], base[loop_face[j]], C,
                      [&](double sine) { ok = ok && sine > kFoamMargin; });
  return ok;
}

double foam_cell_violation(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points,
                           std::span<const PointId> base, std::span<const std::uint32_t> loop_face) {
  thread_local std::vector<Point3> F;
  const Point3 C = cell_centre_and_faces(s, c, points, F);
  double v = 0;
  const std::uint32_t j0 = s.cell_loop_off[c];
  for (std::uint32_t j = j0; j < s.cell_loop_off[c + 1]; ++j)
    for_each_foam_tet(s.loop(j), points, F[j - j0], base[loop_face[j]], C, [&](double sine) {
      if (!(sine > 2 * kFoamMargin)) v += std::isfinite(sine) ? 2 * kFoamMargin - sine : 2.0;
    });
  return v;
}

FoamCheck foam_check(const PolyMesh& mesh) {
  const MeshStencil s = build_stencil(mesh);
  const std::vector<Point3> C = foam_cell_centres(s, mesh.points);
  const std::span<const Point3> pts = mesh.points;
  FoamCheck r;
  std::vector<char> bad_cell(mesh.num_cells(), 0);
  std::vector<PointId> loop[2];
  for (std::uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const CellId cell[2] = {mesh.face_owner[f], mesh.face_neighbour[f]};
    bool pyramid_bad = false, tets_bad = false;
    for (int side = 0; side < 2; ++side) {
      if (!cell[side].valid()) continue;
      outward_loop(mesh, f, side, loop[side]);
      Vec3 a;
      const Point3 fc = foam_face_centre(loop[side], pts, &a);
      pyramid_bad |= !(dot(a, fc - C[cell[side].idx]) > 0);
      for_each_foam_tet(loop[side], pts, fc, PointId(), C[cell[side].idx], [&](double sine) { tets_bad |= !(sine > 0); });
    }
    bool any_base = false;  // some base whose fan passes with both centres
    for (std::size_t b = 0; b < loop[0].size() && !any_base; ++b) {
      double m = cell[0].valid() ? fan_min_sine(loop[0], pts, b, C[cell[0].idx]) : 1.0;
      if (cell[1].valid()) m = std::min(m, fan_min_sine(loop[1], pts, loop[0].size() - 1 - b, C[cell[1].idx]));
      any_base = m > 0;
    }
    tets_bad |= !any_base;
    r.pyramid_faces += pyramid_bad;
    r.face_tet_faces += tets_bad;
    if (pyramid_bad || tets_bad)
      for (const CellId c : cell)
        if (c.valid()) bad_cell[c.idx] = 1;
  }
  for (std::uint32_t c = 0; c < bad_cell.size(); ++c)
    if (bad_cell[c]) r.cells.push_back(c);
  return r;
}

Json FoamCheck::to_json() const {
  Json j = Json::object();
  j.set("pyramid_faces", pyramid_faces);
  j.set("face_tet_faces", face_tet_faces);
  j.set("cells", cells.size());
  return j;
}

}  // namespace polydual
