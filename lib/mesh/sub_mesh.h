// A sub-mesh of a ClassifiedTetMesh: some of its tets, with their vertices,
// regions, input numbering and classification (vertices, edges, model-face
// triangles, the model) carried over. The sub-mesh's boundary where it cuts
// through the mesh is not a model boundary: its triangles keep their class in
// the whole mesh (kNoFace for an interior one), so it is a valid input only
// for readers that never look past the stars they need (the split's local
// rounds, split/local_round.h, with dual/build_dual.h's DualScope). Also the
// shape of a partition's piece for a distributed dual later.
//
// Vertices and tets keep their relative order (both are listed increasing),
// so every entity whose tets are all in the sub-mesh keeps its stored tet,
// local index and orientation: the sub-mesh's edge (a, b), triangle and star
// of such an entity read exactly as in the whole mesh.
#pragma once
#include <span>
#include <vector>

#include "mesh/classified_tet_mesh.h"

namespace polydual {

struct SubMesh {
  ClassifiedTetMesh mesh;
  std::vector<VertexId> vertex;  // sub-mesh vertex -> whole mesh vertex, increasing
  std::vector<TetId> tet;        // sub-mesh tet -> whole mesh tet, increasing
};

// The sub-mesh of the given tets (increasing, no repeats; throws
// std::invalid_argument otherwise).
SubMesh sub_mesh(const ClassifiedTetMesh& m, std::span<const TetId> tets);

// The tets of the stars of the given vertices (any order, repeats allowed),
// increasing.
std::vector<TetId> star_tets(const ClassifiedTetMesh& m, std::span<const VertexId> vertices);

}  // namespace polydual
