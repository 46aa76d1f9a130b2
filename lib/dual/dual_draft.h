// The dual before its cleanup and its cells (design §4 steps 1-7): what
// build_dual_draft() produces and cleanup_dual() and assemble_cells() consume.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/handles.h"
#include "mesh/poly_mesh.h"

namespace polydual {

struct DualDraft {
  // Points (with their classification) and faces (loops, owner, neighbour,
  // kind, tag), and per cell its material and primal vertex (input
  // numbering); cell_offsets / cell_faces are empty until assemble_cells().
  PolyMesh mesh;
  std::size_t num_cells = 0;

  // Coincidence hints, found by the builder while the centres' error bounds
  // were in memory (they are freed before the faces are made, at the memory
  // peak). Empty when the cleanup is off.
  //
  // Pairs of points that coincide exactly, decided with the primal's exact
  // predicates: face-adjacent well-centred cospherical tets of one region, and
  // adjacent well-centred cocircular triangles of one model face.
  std::vector<std::pair<PointId, PointId>> exact_pairs;
  // Pairs of tet centres joined by a dual edge (across a triangle on no model
  // face) that are closer than collapse_length.
  std::vector<std::pair<PointId, PointId>> short_pairs;
  // Sorted ids of the faces with an edge that short_pairs does not cover (the
  // faces with a model point: bounded fans and caps); the cleanup walks only
  // their loops for short edges.
  std::vector<std::uint32_t> scan_faces;
  // Per point (empty: none): pinned by a whole-cut vertex (dual/vertex_cuts.h),
  // never collapsed.
  std::vector<char> pinned;
  // Absolute length (model units) below which an edge between two points of
  // equal classification is collapsed; 0: no collapse.
  double collapse_length = 0;
  // Built in BoundaryMode::Keep: points on model entities never collapse
  // (each lies on its own primal triangle, edge or vertex, and a collapse
  // would move it off the boundary triangulation).
  bool keep_boundary = false;
  // Built with a DualScope (build_dual.h): most points belong to no built
  // face. Such a dual lives for one split round only, so the cleanup drops
  // those points without shrinking the arrays (a shrink copies them, and in
  // the split's first local round that copy was the process's memory peak).
  bool scoped = false;
};

}  // namespace polydual
