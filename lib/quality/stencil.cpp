#include "quality/stencil.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>

namespace polydual {

namespace {

constexpr std::size_t kCellGrain = 256;

// Exclusive prefix sum in place over off[1..]: off[i+1] += off[i].
void prefix_sum(std::vector<std::uint32_t>& off) {
  for (std::size_t i = 1; i < off.size(); ++i) off[i] += off[i - 1];
}

// One thread's per-point scratch: stamp[p] == gen while p is among the current
// cell's points, local[p] its index in the cell's list.
struct CellLister {
  explicit CellLister(std::size_t np) : stamp(np, 0), local(np, 0) {}
  std::vector<std::uint32_t> stamp, local;
  std::uint32_t gen = 0;
  void next_cell() {
    if (++gen == 0) {  // wrapped: every stamp is stale
      std::fill(stamp.begin(), stamp.end(), 0u);
      gen = 1;
    }
  }
};

// Cell c's loops (outward order), its distinct points in first-seen order and
// each loop point's local index, written at the offsets already computed.
void fill_cell(const PolyMesh& mesh, std::uint32_t c, CellLister& ls, MeshStencil& s) {
  ls.next_cell();
  std::uint32_t n = 0;
  PointId* pts = s.cell_pts.data() + s.cell_pt_off[c];
  std::uint32_t j = s.cell_loop_off[c];
  for (HalfFace h : mesh.cell(CellId(c))) {
    const auto f = mesh.face(h.face());
    const std::size_t k = f.size();
    std::uint32_t i_out = s.loop_off[j++];
    for (std::size_t i = 0; i < k; ++i, ++i_out) {
      // Side 1 sees the owner's loop reversed: its outward order is f[k-1-i].
      const PointId p = h.side() == 0 ? f[i] : f[k - 1 - i];
      if (ls.stamp[p.idx] != ls.gen) {
        ls.stamp[p.idx] = ls.gen;
        ls.local[p.idx] = n;
        pts[n++] = p;
      }
      s.loop_pts[i_out] = p;
      if (!s.loop_local.empty()) s.loop_local[i_out] = ls.local[p.idx];
    }
  }
}

// Point -> cells, each point's cells increasing: counted and placed by atomic
// cursors in parallel, then each point's few cells sorted (the order of the
// placement does not matter, so the result does not depend on the threads).
void build_point_cells(MeshStencil& s, std::size_t np) {
  const std::size_t nc = s.num_cells();
  s.point_cell_off.assign(np + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, kCellGrain), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c)
      for (PointId p : s.points_of(static_cast<std::uint32_t>(c)))
        std::atomic_ref<std::uint32_t>(s.point_cell_off[p.idx + 1]).fetch_add(1, std::memory_order_relaxed);
  });
  prefix_sum(s.point_cell_off);
  s.point_cells.resize(s.cell_pts.size());
  std::vector<std::uint32_t> fill(s.point_cell_off.begin(), s.point_cell_off.end() - 1);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, kCellGrain), [&](const auto& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c)
      for (PointId p : s.points_of(static_cast<std::uint32_t>(c))) {
        const std::uint32_t at = std::atomic_ref<std::uint32_t>(fill[p.idx]).fetch_add(1, std::memory_order_relaxed);
        s.point_cells[at] = static_cast<std::uint32_t>(c);
      }
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 4096), [&](const auto& r) {
    for (std::size_t p = r.begin(); p != r.end(); ++p)
      std::sort(s.point_cells.begin() + s.point_cell_off[p], s.point_cells.begin() + s.point_cell_off[p + 1]);
  });
}

}  // namespace

// Two parallel passes over the cells: the sizes (loops from the half-faces,
// distinct points by a per-thread stamp), then, at the prefix-summed offsets,
// the lists themselves. Every array is sized once, so nothing is copied as it
// grows; the result is the same for any number of threads.
MeshStencil build_stencil(const PolyMesh& mesh, bool local_indices) {
  MeshStencil s;
  const std::size_t nc = mesh.num_cells(), np = mesh.num_points(), nh = mesh.cell_faces.size();
  s.cell_loop_off.assign(mesh.cell_offsets.begin(), mesh.cell_offsets.end());  // a loop per half-face
  s.loop_off.assign(nh + 1, 0);
  s.cell_pt_off.assign(nc + 1, 0);
  tbb::enumerable_thread_specific<CellLister> listers([np] { return CellLister(np); });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, kCellGrain), [&](const auto& r) {
    CellLister& ls = listers.local();
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      ls.next_cell();
      std::uint32_t n = 0;
      for (std::uint32_t j = s.cell_loop_off[c]; j < s.cell_loop_off[c + 1]; ++j) {
        const auto f = mesh.face(mesh.cell_faces[j].face());
        s.loop_off[j + 1] = static_cast<std::uint32_t>(f.size());
        for (PointId p : f)
          if (ls.stamp[p.idx] != ls.gen) { ls.stamp[p.idx] = ls.gen; ++n; }
      }
      s.cell_pt_off[c + 1] = n;
    }
  });
  prefix_sum(s.loop_off);
  prefix_sum(s.cell_pt_off);
  s.cell_pts.resize(s.cell_pt_off.back());
  s.loop_pts.resize(s.loop_off.back());
  if (local_indices) s.loop_local.resize(s.loop_off.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, kCellGrain), [&](const auto& r) {
    CellLister& ls = listers.local();
    for (std::size_t c = r.begin(); c != r.end(); ++c) fill_cell(mesh, static_cast<std::uint32_t>(c), ls, s);
  });
  build_point_cells(s, np);
  return s;
}

}  // namespace polydual
