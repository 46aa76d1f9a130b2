// Writing a PolyMesh in any supported format, beside the reader dispatcher
// (read_tet_mesh.h). New formats (Exodus II, CGNS, decomposed cases) add an
// enumerator, a name and a branch here; the pipeline and the command do not
// change.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/json.h"
#include "io/foam_writer.h"
#include "io/vtu_poly_writer.h"
#include "mesh/poly_mesh.h"

namespace polydual {

enum class PolyFormat : std::uint8_t {
  Vtu,   // VTK XML UnstructuredGrid, VTK_POLYHEDRON cells (a file)
  Foam,  // OpenFOAM case (a directory; OUT/constant/polyMesh)
};

const char* poly_format_name(PolyFormat f);
// "vtu" | "foam"; throws UsageError naming the accepted values.
PolyFormat parse_poly_format(std::string_view name);
// The format of an output path: *.vtu -> Vtu; a name without an extension
// or ending in '/' -> Foam (a case directory); any other extension is a
// UsageError (an output is never written under a name that says otherwise).
// A non-empty `requested` name wins over the path.
PolyFormat poly_format_for(std::string_view requested, const std::string& path);

struct PolyWriteOptions {
  // Appended raw binary (VTK's own default): streamed to the file, no
  // encoding, the fastest to write and to read.
  VtuOptions vtu{true, true};
  FoamOptions foam;
};

// Writes `mesh` (and, for VTU, the extra cell arrays) to `path` atomically;
// returns {"path", "format", and the writer's own record}.
Json write_poly_mesh(const PolyMesh& mesh, const std::string& path, PolyFormat format,
                     const std::vector<CellField>& cell_fields = {}, const PolyWriteOptions& options = {});

}  // namespace polydual
