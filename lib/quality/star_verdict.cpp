#include "quality/star_verdict.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "predicates/predicates.h"

namespace polydual {

CellVerdict star_shaped_verdict(const MeshStencil& s, std::uint32_t c,
                                std::span<const Point3> points, bool stop_at_first_bad,
                                std::vector<Point3>& scratch) {
  // scratch = [cell points | current face points].
  const auto cp = s.points_of(c);
  scratch.clear();
  for (PointId p : cp) scratch.push_back(points[p.idx]);
  const std::size_t m = scratch.size();
  CellVerdict v;
  for (std::uint32_t j = s.cell_loop_off[c]; j < s.cell_loop_off[c + 1]; ++j) {
    const auto loop = s.loop(j);
    scratch.resize(m);
    for (PointId p : loop) scratch.push_back(points[p.idx]);
    const std::span<const Point3> cell(scratch.data(), m);
    const std::span<const Point3> face(scratch.data() + m, loop.size());
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Point3& a = face[i];
      const Point3& b = face[(i + 1) % loop.size()];
      ++v.total_tets;
      if (decomposition_tet_sign(a, b, face, cell) != Sign::Positive) {
        v.valid = false;
        ++v.bad_tets;
        if (stop_at_first_bad) return v;
      }
    }
  }
  return v;
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

std::vector<CellVerdict> star_shaped_verdicts(const PolyMesh& mesh) {
  const MeshStencil s = build_stencil(mesh);
  std::vector<CellVerdict> out(mesh.num_cells());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), 256), [&](const auto& r) {
    std::vector<Point3> scratch;
    for (std::size_t c = r.begin(); c != r.end(); ++c)
      out[c] = star_shaped_verdict(s, static_cast<std::uint32_t>(c), mesh.points, false, scratch);
  });
  return out;
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
