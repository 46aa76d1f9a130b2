#include "quality/stencil.h"

#include <algorithm>

namespace polydual {

MeshStencil build_stencil(const PolyMesh& mesh) {
  MeshStencil s;
  const std::size_t nc = mesh.num_cells(), np = mesh.num_points();
  s.cell_pt_off.reserve(nc + 1);
  s.cell_loop_off.reserve(nc + 1);
  s.cell_pts.reserve(mesh.cell_faces.size() * 2);
  s.loop_pts.reserve(mesh.cell_faces.size() * 5);
  std::vector<std::uint32_t> seen(np, UINT32_MAX);  // seen[p] == c: p already listed for c
  std::vector<std::uint32_t> local(np, 0);          // p's index in c's point list
  for (std::uint32_t c = 0; c < nc; ++c) {
    for (HalfFace h : mesh.cell(CellId(c))) {
      const auto f = mesh.face(h.face());
      const std::size_t k = f.size();
      for (std::size_t i = 0; i < k; ++i) {
        // Side 1 sees the owner's loop reversed: its outward order is f[k-1-i].
        const PointId p = h.side() == 0 ? f[i] : f[k - 1 - i];
        s.loop_pts.push_back(p);
        if (seen[p.idx] != c) {
          seen[p.idx] = c;
          local[p.idx] = static_cast<std::uint32_t>(s.cell_pts.size() - s.cell_pt_off.back());
          s.cell_pts.push_back(p);
        }
        s.loop_local.push_back(local[p.idx]);
      }
      s.loop_off.push_back(static_cast<std::uint32_t>(s.loop_pts.size()));
    }
    s.cell_pt_off.push_back(static_cast<std::uint32_t>(s.cell_pts.size()));
    s.cell_loop_off.push_back(static_cast<std::uint32_t>(s.loop_off.size() - 1));
  }
  // Point -> cells (counting sort keeps cells increasing per point).
  s.point_cell_off.assign(np + 1, 0);
  for (PointId p : s.cell_pts) ++s.point_cell_off[p.idx + 1];
  for (std::size_t p = 0; p < np; ++p) s.point_cell_off[p + 1] += s.point_cell_off[p];
  s.point_cells.resize(s.cell_pts.size());
  std::vector<std::uint32_t> fill(s.point_cell_off.begin(), s.point_cell_off.end() - 1);
  for (std::uint32_t c = 0; c < nc; ++c)
    for (PointId p : s.points_of(c)) s.point_cells[fill[p.idx]++] = c;
  return s;
}

}  // namespace polydual
