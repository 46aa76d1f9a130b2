// VTK XML UnstructuredGrid (.vtu) reader: tets (cell type 10) and triangles
// (5) with a cell-data region array; vertex (1) and line (3) cells, which
// meshio writes for Gmsh's point and curve elements, are skipped. DataArrays
// may be in any format VTK or meshio writes (ascii, inline base64, appended
// raw or base64, zlib-compressed; UInt32 or UInt64 headers: lib/io/vtk_xml.h).
// The region array is the first cell array found in this order: region,
// material, gmsh:physical, medit:ref, CellEntityIds (it must have an integer
// type); tets take its value as region and triangles as model face tag.
// Without one every tet has region 1 (triangles tag 0).
//
// Hand-written (no VTK dependency) so errors name the line or byte, and the
// reader works on memory buffers for fuzzing.
#pragma once
#include <string>
#include <string_view>

#include "mesh/tet_soup.h"

namespace polydual {

TetSoup read_vtu(std::string_view bytes, const std::string& source);
TetSoup read_vtu_file(const std::string& path);

}  // namespace polydual
