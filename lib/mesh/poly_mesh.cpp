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

std::vector<PointId> PolyMesh::oriented_loop(HalfFace h) const {
  auto f = face(h.face());
  std::vector<PointId> loop(f.begin(), f.end());
  if (h.side() == 1) std::reverse(loop.begin(), loop.end());
  return loop;
}

}  // namespace polydual
