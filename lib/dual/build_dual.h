// The dual mesh (SPEC §4, paper Algorithm 1): one polyhedral cell per side of
// every primal vertex, conformal across interfaces and fractures, with every
// model vertex, edge and face represented.
#pragma once
#include <cstdint>

#include "core/json.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"

namespace polydual {

struct DualParams {
  // Run the cleanup (SPEC §4.9): exact merge of coincident dual points, then
  // collapse of short edges. Default on.
  bool cleanup = true;
  // Edges shorter than collapse_tolerance x (mean primal edge length) are
  // collapsed (only between points of the same classification). 0 disables.
  double collapse_tolerance = 1e-3;
};

struct DualStats {
  std::size_t well_centred_tets = 0, clamped_tets = 0;
  std::size_t well_centred_triangles = 0, clamped_triangles = 0;
  std::size_t merged_points = 0;      // by the exact cospherical merge
  std::size_t collapsed_points = 0;   // by the short-edge collapse
  std::size_t dropped_faces = 0;      // faces that degenerated below 3 points
  std::size_t slit_faces = 0;         // owner == neighbour (fracture tips)
  double seconds_points = 0, seconds_sides = 0, seconds_faces = 0, seconds_cleanup = 0, seconds_cells = 0;
  Json to_json() const;
};

PolyMesh build_dual(const ClassifiedTetMesh& mesh, const DualParams& params = {},
                    DualStats* stats = nullptr);

}  // namespace polydual
