// OpenFOAM polyMesh writer (design §9): CASE/constant/polyMesh/{points, faces,
// owner, neighbour, boundary, cellZones, faceZones} plus, optionally, a minimal
// CASE/system so OpenFOAM's tools (checkMesh) run on the case. Only
// constant/polyMesh is ever replaced; a user's 0/, system/, other files in
// constant/ and anything else in CASE are left as they were (io/output_guard.h).
//
// OpenFOAM's rules, and what this writer does to meet them:
//  - owner < neighbour on every internal face, the face normal pointing from
//    owner to neighbour: faces whose PolyMesh owner is the larger cell are
//    flipped (loop reversed);
//  - internal faces first, in upper-triangular order (by owner, then neighbour;
//    ties by PolyMesh face id), then boundary faces grouped by patch;
//  - one patch per external model face tag (and per model face tag holding slit
//    faces), "face_<tag>" or the model face's name (see write_foam), increasing
//    tag order;
//    boundary faces that are not FaceKind::External (should not happen in a valid
//    dual) go to a last patch "defaultFaces";
//  - a slit face (owner == neighbour, at fracture tips; its cell lists it twice
//    in opposite senses) has no internal-face form: it is written as a baffle,
//    two boundary faces owned by the cell (the loop and its reverse), in the
//    patch "face_<tag>" of its model face tag, so every half-face of the cell
//    has its own face and the case is closed;
//  - points used only by dropped faces are dropped too (checkMesh fails on
//    unused points);
//  - OpenFOAM rejects a face that repeats a point: spurs "a b a" (zero area,
//    e.g. a cap passing twice through a model-edge midpoint) are cut out of the
//    loop, and a face left with < 3 points is dropped (both counted);
//  - cellZones "material_<tag>" per material; faceZones "interface_<tag>" and
//    "fracture_<tag>" per Interface/Fracture face tag (or the entity's name). flipMap: an interface
//    zone is oriented from the lower material tag to the higher; a fracture zone
//    keeps the PolyMesh orientation (owner -> neighbour) of each face.
// Points carry 17 significant digits (exact double round trip).
#pragma once
#include <cstddef>
#include <string>

#include "core/json.h"
#include "io/model_names.h"
#include "mesh/poly_mesh.h"

namespace polydual {

struct FoamOptions {
  // OpenFOAM patch type of the external patches ("patch" or "wall").
  std::string patch_type = "patch";
  // Also write system/{controlDict,fvSchemes,fvSolution} (OpenFOAM tools need
  // them) when the case has no system/ yet; an existing system/ is never touched.
  bool write_system = true;
  // Write into an existing directory that is not a case (neither empty nor
  // with constant/ or system/), leaving its files; refused otherwise.
  bool force = false;
};

struct FoamReport {
  std::size_t points = 0, cells = 0, faces = 0, internal_faces = 0;
  std::size_t patches = 0, cell_zones = 0, face_zones = 0;
  std::size_t slit_faces = 0;          // owner == neighbour faces, each written twice
  std::size_t dropped_points = 0;      // points used only by dropped faces / spurs
  std::size_t faces_without_spurs = 0;       // faces written with spurs removed
  std::size_t dropped_degenerate_faces = 0;  // faces that were nothing but spurs
  Json to_json() const;
};

// Writes the case into `case_dir`: the new polyMesh is built in a temporary
// directory inside case_dir/constant and swapped in for the old one (core/
// atomic_file.h), then system/ is added if absent (also built aside and renamed
// in). On any failure (WriteError, Interrupted) either the old or the new
// polyMesh is complete, no temporary remains, and directories that this call
// created are removed again; the error propagates.
// Throws UsageError when `case_dir` may not be written (check_case_directory),
// InputError("<memory>", "face N", ...) for a face without any cell.
// With `names`, a patch, cell zone or face zone whose model entity is named
// takes the name as an OpenFOAM word (bytes other than letters, digits, '_',
// '.', '-' become '_'; a leading '_' where it would not start with a letter
// or '_'; "_2", "_3", ... where two names would clash), and the entities of
// one name are one patch or zone (at the place of the first). Without names
// the case is the same bytes as before names existed.
FoamReport write_foam(const PolyMesh& mesh, const std::string& case_dir,
                      const FoamOptions& options = {}, const ModelNames& names = {});

}  // namespace polydual
