#include "quality/star_verdict.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

#include "predicates/predicates.h"

namespace polydual {

namespace {

// The sums of the listed points about origin o (point_sums on indices: no copy).
PointSums point_sums_of(std::span<const PointId> ids, std::span<const Point3> points, const Point3& o) {
  PointSums r;
  r.origin = o;
  r.n = ids.size();
  for (PointId q : ids) {
    const Point3& p = points[q.idx];
    const double dx = p.x - o.x, dy = p.y - o.y, dz = p.z - o.z;
    r.sx += dx; r.sy += dy; r.sz += dz;
    r.ax += std::fabs(dx); r.ay += std::fabs(dy); r.az += std::fabs(dz);
  }
  return r;
}

// The exact sign of one decomposition tet the summed filter left undecided:
// the cell's and the face's points copied into scratch for the per-tet filter
// and the exact fallback (rare).
Sign undecided_tet_sign(const MeshStencil& s, std::uint32_t c, std::span<const PointId> loop, std::size_t i,
                        std::span<const Point3> points, std::vector<Point3>& scratch) {
  scratch.clear();
  for (PointId q : s.points_of(c)) scratch.push_back(points[q.idx]);
  const std::size_t m = scratch.size();
  for (PointId q : loop) scratch.push_back(points[q.idx]);
  const std::span<const Point3> cell(scratch.data(), m), face(scratch.data() + m, loop.size());
  return decomposition_tet_sign(face[i], face[(i + 1) % loop.size()], face, cell);
}

// The verdict of cell c; on_bad(j, i) for each non-positive tet (loop j,
// edge i); it returns whether to stop there.
template <class OnBad>
CellVerdict stencil_verdict(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points,
                            std::vector<Point3>& scratch, OnBad&& on_bad) {
  // The summed filter decides almost every tet from the cell's and the face's
  // sums, read straight from the points; the rest go exact.
  const auto cp = s.points_of(c);
  CellVerdict v;
  if (cp.empty()) return v;
  const PointSums cs = point_sums_of(cp, points, points[cp[0].idx]);
  for (std::uint32_t j = s.cell_loop_off[c]; j < s.cell_loop_off[c + 1]; ++j) {
    const auto loop = s.loop(j);
    const std::size_t k = loop.size();
    const PointSums fs = point_sums_of(loop, points, cs.origin);
    for (std::size_t i = 0; i < k; ++i) {
      const Point3& a = points[loop[i].idx];
      const Point3& b = points[loop[i + 1 == k ? 0 : i + 1].idx];
      ++v.total_tets;
      Sign sg = decomposition_tet_sign_if_certain(a, b, fs, cs);
      if (sg == Sign::Zero) sg = undecided_tet_sign(s, c, loop, i, points, scratch);
      if (sg != Sign::Positive) {
        v.valid = false;
        ++v.bad_tets;
        if (on_bad(j, i)) return v;
      }
    }
  }
  return v;
}

}  // namespace

CellVerdict star_shaped_verdict(const MeshStencil& s, std::uint32_t c,
                                std::span<const Point3> points, bool stop_at_first_bad,
                                std::vector<Point3>& scratch) {
  return stencil_verdict(s, c, points, scratch, [&](std::uint32_t, std::size_t) { return stop_at_first_bad; });
}

CellVerdict star_shaped_bad_tets(const MeshStencil& s, std::uint32_t c, std::span<const Point3> points,
                                 std::vector<Point3>& scratch,
                                 std::vector<std::pair<std::uint32_t, std::uint32_t>>& bad) {
  bad.clear();
  return stencil_verdict(s, c, points, scratch, [&](std::uint32_t j, std::size_t i) {
    bad.emplace_back(j, static_cast<std::uint32_t>(i));
    return false;
  });
}

CellVerdict star_shaped_verdict(const PolyMesh& mesh, CellId c) {
  std::vector<Point3> cell, face;
  for (PointId p : mesh.cell_points(c)) cell.push_back(mesh.points[p.idx]);
  CellVerdict v;
  for (HalfFace h : mesh.cell(c)) {
    face.clear();
    for (PointId p : mesh.oriented_loop(h)) face.push_back(mesh.points[p.idx]);
    for (std::size_t i = 0; i < face.size(); ++i) {
      ++v.total_tets;
      if (decomposition_tet_sign(face[i], face[(i + 1) % face.size()], face, cell) != Sign::Positive) {
        v.valid = false;
        ++v.bad_tets;
      }
    }
  }
  return v;
}

namespace {

// Per-thread scratch of the verdicts straight from the mesh: `seen[p] ==
// stamp` when point p is already among the current cell's points (one stamp
// per mesh point, ~3 B per input tet and thread, against ~240 for a whole
// MeshStencil). Two-byte stamps, all cleared when the cell count wraps: the
// final check of the split runs next to the whole dual, at the memory peak.
struct MeshScratch {
  std::vector<std::uint16_t> seen;
  std::vector<Point3> points;  // [cell points | current face points]
  std::uint16_t stamp = 0;
  // The stamp of the next cell (every old stamp then differs from it).
  std::uint16_t next_stamp() {
    if (++stamp == 0) {
      std::fill(seen.begin(), seen.end(), std::uint16_t(0));
      stamp = 1;
    }
    return stamp;
  }
};

// The verdict of cell c from the mesh itself, the same decomposition tets as
// the stencil's: the cell's distinct points first seen along its outward loops,
// each loop in the cell's outward order (side 1 reversed).
CellVerdict verdict_from_mesh(const PolyMesh& mesh, std::uint32_t c, MeshScratch& s) {
  const auto cell = mesh.cell(CellId(c));
  s.points.clear();
  const std::uint16_t stamp = s.next_stamp();
  for (HalfFace h : cell) {
    const auto f = mesh.face(h.face());
    const std::size_t k = f.size();
    for (std::size_t i = 0; i < k; ++i) {
      const PointId p = h.side() == 0 ? f[i] : f[k - 1 - i];
      if (s.seen[p.idx] != stamp) {
        s.seen[p.idx] = stamp;
        s.points.push_back(mesh.points[p.idx]);
      }
    }
  }
  const std::size_t m = s.points.size();
  CellVerdict v;
  if (m == 0) return v;
  const PointSums cs = point_sums({s.points.data(), m}, s.points[0]);
  for (HalfFace h : cell) {
    const auto f = mesh.face(h.face());
    const std::size_t k = f.size();
    s.points.resize(m);
    for (std::size_t i = 0; i < k; ++i) s.points.push_back(mesh.points[(h.side() == 0 ? f[i] : f[k - 1 - i]).idx]);
    const std::span<const Point3> cell_pts(s.points.data(), m);
    const std::span<const Point3> face(s.points.data() + m, k);
    const PointSums fs = point_sums(face, cs.origin);
    for (std::size_t i = 0; i < k; ++i) {
      ++v.total_tets;
      if (decomposition_tet_sign(face[i], face[(i + 1) % k], face, cell_pts, fs, cs) != Sign::Positive) {
        v.valid = false;
        ++v.bad_tets;
      }
    }
  }
  return v;
}

}  // namespace

std::vector<CellVerdict> star_shaped_verdicts(const PolyMesh& mesh) {
  std::vector<CellVerdict> out(mesh.num_cells());
  tbb::enumerable_thread_specific<MeshScratch> scratch;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), 256), [&](const auto& r) {
    MeshScratch& s = scratch.local();
    if (s.seen.empty()) s.seen.assign(mesh.num_points(), 0);
    for (std::size_t c = r.begin(); c != r.end(); ++c) out[c] = verdict_from_mesh(mesh, static_cast<std::uint32_t>(c), s);
  });
  return out;
}

void star_shaped_verdicts_of(const PolyMesh& mesh, std::span<const std::uint32_t> cells, std::span<CellVerdict> out,
                             std::span<std::uint32_t> exact) {
  tbb::enumerable_thread_specific<MeshScratch> scratch;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 64), [&](const auto& r) {
    MeshScratch& s = scratch.local();
    if (s.seen.empty()) s.seen.assign(mesh.num_points(), 0);
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::uint32_t c = cells[i];
      const std::uint64_t e0 = star_exact_this_thread();
      out[c] = verdict_from_mesh(mesh, c, s);
      if (!exact.empty()) exact[c] = std::uint32_t(star_exact_this_thread() - e0);
    }
  });
}

std::size_t count_invalid_cells(const MeshStencil& s, std::span<const Point3> points) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, s.num_cells(), 256), std::size_t{0},
      [&](const auto& r, std::size_t acc) {
        std::vector<Point3> scratch;
        for (std::size_t c = r.begin(); c != r.end(); ++c)
          acc += !star_shaped_verdict(s, static_cast<std::uint32_t>(c), points, true, scratch).valid;
        return acc;
      },
      std::plus<>());
}

}  // namespace polydual
