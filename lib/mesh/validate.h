// Invariant checks on a PolyMesh (SPEC §10), used by tests, by the CLI's
// `check` and between stages. Combinatorial checks are exact by nature; the
// volumes are double sums (statistics; the exact identity is checked in tests).
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/json.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"

namespace polydual {

struct ValidationReport {
  std::size_t cells = 0, faces = 0, points = 0;
  std::size_t closed_cells = 0;          // every cell edge balanced (as often forward as backward)
  std::size_t manifold_cells = 0;        // closed, and every edge used by exactly two half-faces
  std::size_t slit_cells = 0;            // cells holding both sides of a face (fracture tips)
  std::vector<CellId> open_cells;        // not closed (first 100)
  std::size_t face_errors = 0;           // faces with < 3 points, repeated points, bad owner/neighbour
  std::size_t negative_volume_cells = 0;  // geometry, not topology: tangled cells (reported, not an error)
  std::map<std::int32_t, double> material_volume;  // sum of decomposition volumes (double)
  std::vector<std::string> missing_model_entities;  // "vertex 3", "edge 7", "face 2"
  bool ok() const {
    return closed_cells == cells && face_errors == 0 && missing_model_entities.empty();
  }
  Json to_json() const;
};

// primal may be null: then model-entity representation is not checked.
ValidationReport validate(const PolyMesh& mesh, const ClassifiedTetMesh* primal = nullptr);

// Signed volume of a cell by its symmetric decomposition (double).
double cell_volume(const PolyMesh& mesh, CellId c);

}  // namespace polydual
