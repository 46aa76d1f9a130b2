// STEP 7 of Algorithm 1 on a PrimalMesh (dual/primal_dual.h): the capping
// faces round the vertices on model faces, the rules of build_dual.cpp's
// make_caps without cuts. Internal to the mixed dual builder.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "dual/build_dual.h"
#include "dual/primal_sides.h"
#include "mesh/primal_mesh.h"

namespace polydual {

// The dual points of a PrimalMesh's entities (cells: PointId == PrimalCellId).
struct MixedPoints {
  std::vector<PointId> face_pt;  // per face: its central point on a model face, else invalid
  std::vector<PointId> edge_pt;  // per edge: its midpoint when it has one
  std::vector<PointId> vert_pt;  // per vertex: itself when it is a dual point
  // Per cell: a well-centred tet's centre error bound (central_points.h),
  // -inf otherwise (no tolerance admits it in the coincidence test).
  std::vector<double> cell_error;
  std::vector<char> face_merge;  // per face: a well-centred model-face triangle (caps mode)
  // Per vertex: cut whole (the mixed split); empty: none. Every face and
  // edge through such a vertex has a point (its vertex mean, its midpoint),
  // and so has the vertex.
  std::vector<char> whole;
  bool is_whole(VertexId v) const { return !whole.empty() && whole[v.idx]; }
};

// A face's place in the order (owner cell, local face): on a tet mesh the
// order of the tet builder's TriIds. Model-face points are numbered in it and
// caps walk faces in it, so that the cleanup (which keeps the smallest id of
// merged points) and a cap cut in two (a pole) match the tet builder's.
std::uint64_t owner_order(const PrimalMesh& m, PrimalFaceId f);

// Appends the caps (keep: the tiles of the model faces) of every vertex on a
// model face that is not cut whole, and the tiles (v, mid, centre, mid) of
// every face through a vertex cut whole (its corners' walls, design §14);
// kinds: primal_face_kinds(m).
void make_primal_caps(const PrimalMesh& m, const PrimalSides& sides, const MixedPoints& d,
                      const std::vector<std::pair<std::int32_t, FaceKind>>& kinds, bool keep, PolyMesh& pm,
                      DualStats& st);

}  // namespace polydual
