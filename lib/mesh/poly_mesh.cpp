#include "mesh/poly_mesh.h"

#include <algorithm>
#include <unordered_set>

namespace polydual {

std::vector<PointId> PolyMesh::cell_points(CellId c) const {
  std::vector<PointId> out;
  for (HalfFace h : cell(c))
    for (PointId p : face(h.face()))
      if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  return out;
}

std::span<const PointId> CellPointScan::operator()(CellId c) {
  if (++gen_ == 0) {  // wrapped: every stamp is stale
    std::fill(stamp_.begin(), stamp_.end(), std::uint16_t(0));
    gen_ = 1;
  }
  out_.clear();
  for (HalfFace h : mesh_->cell(c))
    for (PointId p : mesh_->face(h.face()))
      if (stamp_[p.idx] != gen_) {
        stamp_[p.idx] = gen_;
        out_.push_back(p);
      }
  return out_;
}

std::vector<PointId> PolyMesh::oriented_loop(HalfFace h) const {
  auto f = face(h.face());
  std::vector<PointId> loop(f.begin(), f.end());
  if (h.side() == 1) std::reverse(loop.begin(), loop.end());
  return loop;
}

}  // namespace polydual
