// VTK XML UnstructuredGrid (.vtu) of a surface dual (mesh/poly_surface.h):
// one VTK_POLYGON cell (type 7) per polygon, its points counterclockwise in
// the surface's orientation.
//   CellData   surface (Int32), primal_vertex (Int64, input numbering), then
//              the caller's arrays (e.g. "valid");
//   PointData  class_dim (Int8), class_tag (Int32): each point's model entity.
// ASCII, or base64 "binary" inside each DataArray (header UInt64, header and
// data encoded separately as VTK does), zlib-compressed at options.zlib_level;
// options.appended is written as inline binary (a surface dual is small).
#pragma once
#include <string>
#include <vector>

#include "io/vtu_poly_writer.h"
#include "mesh/poly_surface.h"

namespace polydual {

// Atomically (core/atomic_file.h); same surface and options -> same bytes.
// UsageError for an extra array of the wrong size or a built-in name, or a
// zlib level outside 0..9 or with ASCII.
void write_vtu_surface(const PolySurface& s, const std::string& path, const std::vector<CellField>& extra = {},
                       const VtuOptions& options = {});

}  // namespace polydual
