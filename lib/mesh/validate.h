// Invariant checks on a PolyMesh (design §10), used by tests, by the CLI's
// `check` and between stages. Combinatorial checks are exact by nature; the
// volumes are double sums compared with a relative tolerance (the exact
// identity is checked with rationals in tests/dual/dual_test.cpp).
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/json.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/poly_mesh.h"

namespace polydual {

// Default relative tolerance of the per-material volume check:
// |dual - primal| <= tol * max(|dual|, |primal|). Both sides are double sums of
// one positive-dominated term per tet or decomposition tet, each rounded a few
// times, so their relative error is below n * 4 eps (about 1e-9 for n = 2e6
// cells in the worst case, ~1e-13 in practice: errors of independent terms
// do not add up in one direction). A missing, duplicated or displaced cell
// changes a material's volume by about 1/n of it, far above this.
inline constexpr double kVolumeRelTol = 1e-9;

// A material whose dual volume differs from its primal volume.
struct VolumeMismatch {
  std::int32_t material = 0;
  double dual = 0, primal = 0;
  double rel_diff = 0;  // |dual - primal| / max(|dual|, |primal|)
};

// [{"material", "dual", "primal", "rel_diff"}, ...]
Json volume_mismatches_json(const std::vector<VolumeMismatch>& mismatches);

// At most this many cells (faces) of each kind of defect are kept in a report.
inline constexpr std::size_t kListedDefects = 100;

// One failed check of a report, for people: what it means, how many cells,
// faces, model entities or materials fail it and the first kListedDefects of
// them ("cell 12", "face 7 (owner 3, neighbour 4)", "model edge 7",
// "material 2: dual 0.5, primal 0.6").
struct Defect {
  std::string check;    // "open_cells", "face_errors", "missing_model_entities", "volume_mismatches"
  std::string meaning;  // what fails, in a few words, plural ("cells not closed (...)")
  std::size_t count = 0;
  std::vector<std::string> items;
};

struct ValidationReport {
  std::size_t cells = 0, faces = 0, points = 0;
  std::size_t closed_cells = 0;          // every cell edge balanced (as often forward as backward)
  std::size_t manifold_cells = 0;        // closed, and every edge used by exactly two half-faces
  std::size_t slit_cells = 0;            // cells holding both sides of a face (fracture tips)
  // Cells that are not closed because an edge is used at least twice more in
  // one direction than in the other: a face loop reversed (wrongly oriented)
  // rather than a face missing. Counted in cells - closed_cells too.
  std::size_t misoriented_cells = 0;
  std::vector<CellId> open_cells;        // not closed (first kListedDefects)
  std::vector<CellId> misoriented_list;  // misoriented (first kListedDefects)
  // Faces with < 3 points, a repeated point, a point id out of range, an owner
  // or neighbour out of range or missing, a kind that disagrees with the
  // neighbour (External iff none), or a half-face not listed exactly once by
  // its cell (once for the owner, once for a neighbour, never for none). A
  // half-face listed by the wrong cell or naming no face is counted too.
  std::size_t face_errors = 0;
  // The faces with an error of their own or listed wrongly by the cells (a
  // half-face missing or twice), and the cells listing a half-face that is not
  // theirs or names no face (each the first kListedDefects, increasing).
  std::vector<FaceId> error_faces;
  std::vector<CellId> error_cells;
  std::size_t error_face_count = 0, error_cell_count = 0;  // all of them
  std::size_t negative_volume_cells = 0;  // geometry, not topology: tangled cells (reported, not an error)
  std::map<std::int32_t, double> material_volume;  // sum of decomposition volumes (double)
  // With a primal: a model vertex with no dual point classified on it at its
  // position, a model edge with no dual edge along it (both ends on the edge or
  // its model vertices, one on the edge), a model face with no dual face of its
  // tag: "model vertex 3", "model edge 7", "model face 2".
  std::vector<std::string> missing_model_entities;

  // Geometry, with a primal only: per-material volume of the primal (sum of tet
  // volumes, double) and the dual materials that differ from it by more than
  // the tolerance. Only materials all of whose external and interface model
  // faces are planar (exact orientation test on the primal's triangles) are
  // compared: on a curved or jagged model face the dual faces are fans off the
  // primal facets and the volumes differ by the discretisation, not by a bug.
  std::map<std::int32_t, double> primal_material_volume;
  std::vector<std::int32_t> volume_checked_materials;  // sorted
  double volume_rel_tol = kVolumeRelTol;
  std::vector<VolumeMismatch> volume_mismatches;

  // Topology only: closed cells, sound faces, every model entity represented.
  bool ok() const {
    return closed_cells == cells && face_errors == 0 && missing_model_entities.empty();
  }
  // Geometry: every checked material's dual volume matches the primal's.
  bool geometry_ok() const { return volume_mismatches.empty(); }
  // The checks that fail (ok() and geometry_ok() both true: none), in the
  // order: open cells, face errors, missing model entities, volume mismatches.
  std::vector<Defect> defects() const;
  Json to_json() const;
};

// One line per defect: "open_cells: 2 cells not closed (...): cell 12, cell 40"
// with at most `shown` items, then "and N more".
std::string defect_line(const Defect& d, std::size_t shown = 10);
// Every defect's line joined by "; " ("" when there is none), for one error.
std::string defects_sentence(const std::vector<Defect>& defects, std::size_t shown = 10);
// [{"check", "meaning", "count", "items"}, ...]
Json defects_json(const std::vector<Defect>& defects);

// What validate() checks a dual against, from any primal (a tet mesh here,
// a mixed PrimalMesh in quality/check_result.h): its model entities and its
// per-material volumes.
struct PrimalReference {
  // Model vertices (tag, position), and (model edge tag, model vertex tag)
  // for each model vertex that bounds a model edge.
  std::set<std::tuple<std::int32_t, double, double, double>> model_vertices;
  std::set<std::pair<std::int32_t, std::int32_t>> edge_vertex;
  // The model entities of dimension 0, 1, 2 that must be represented, by tag
  // (the order in which missing ones are listed).
  std::array<std::vector<std::int32_t>, 3> entities;
  std::map<std::int32_t, double> material_volume;  // sum of cell volumes (double)
  // Regions bounded (external or interface) by a model face that is not
  // planar, as decided exactly by whoever built the reference: their volume
  // is not compared.
  std::set<std::int32_t> curved_regions;
};

// The reference of a classified tet mesh (planarity: ModelEntity::planar).
PrimalReference primal_reference(const ClassifiedTetMesh& primal);

// primal may be null: then neither model-entity representation nor volumes
// are checked. volume_rel_tol: see kVolumeRelTol.
ValidationReport validate(const PolyMesh& mesh, const PrimalReference& primal,
                          double volume_rel_tol = kVolumeRelTol);
ValidationReport validate(const PolyMesh& mesh, const ClassifiedTetMesh* primal = nullptr,
                          double volume_rel_tol = kVolumeRelTol);

// Signed volume of a cell by its symmetric decomposition (double).
double cell_volume(const PolyMesh& mesh, CellId c);

}  // namespace polydual
