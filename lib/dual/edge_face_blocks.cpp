// Blocks of fan faces (dual/edge_face_blocks.h).
#include "dual/edge_face_blocks.h"

namespace polydual {

void reserve_block(PolyMesh& faces, std::size_t n) {
  faces.face_offsets.reserve(n + 1);
  faces.face_owner.reserve(n);
  faces.face_neighbour.reserve(n);
  faces.face_kind.reserve(n);
  faces.face_tag.reserve(n);
  faces.face_points.reserve(6 * n);
}

void append_faces(PolyMesh& pm, std::vector<std::uint32_t>& model_faces, const EdgeFaceBlock& b) {
  const std::uint32_t f0 = std::uint32_t(pm.num_faces()), p0 = std::uint32_t(pm.face_points.size());
  pm.face_points.insert(pm.face_points.end(), b.faces.face_points.begin(), b.faces.face_points.end());
  for (std::size_t f = 1; f < b.faces.face_offsets.size(); ++f) pm.face_offsets.push_back(p0 + b.faces.face_offsets[f]);
  pm.face_owner.insert(pm.face_owner.end(), b.faces.face_owner.begin(), b.faces.face_owner.end());
  pm.face_neighbour.insert(pm.face_neighbour.end(), b.faces.face_neighbour.begin(), b.faces.face_neighbour.end());
  pm.face_kind.insert(pm.face_kind.end(), b.faces.face_kind.begin(), b.faces.face_kind.end());
  pm.face_tag.insert(pm.face_tag.end(), b.faces.face_tag.begin(), b.faces.face_tag.end());
  for (std::uint32_t f : b.model_faces) model_faces.push_back(f0 + f);
}

}  // namespace polydual
