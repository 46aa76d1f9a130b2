// What a polyhedral writer gets besides the mesh: the options of every
// format, extra cell arrays, and the names of the model's entities (Gmsh
// physical names, carried by classify() into ModelEntity::name), so that an
// OpenFOAM patch or zone, a VTU's field data (and later an Exodus side set or
// a CGNS family) can be named after the input's groups.
#pragma once
#include <vector>

#include "io/foam_writer.h"
#include "io/model_names.h"
#include "io/vtu_poly_writer.h"
#include "mesh/classified_tet_mesh.h"

namespace polydual {

struct PolyWriteOptions {
  // Appended raw binary (VTK's own default): streamed to the file, no
  // encoding, the fastest to write and to read.
  VtuOptions vtu{true, true};
  FoamOptions foam;
};

// The non-empty ModelEntity::name of the model's regions and faces.
ModelNames model_names(const ModelTopology& model);

struct WriteContext {
  PolyWriteOptions options;
  std::vector<CellField> cell_fields;  // written by formats that take cell data (VTU)
  ModelNames names;
};

}  // namespace polydual
