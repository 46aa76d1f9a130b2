// VTK XML UnstructuredGrid (.vtu) reader: tets (cell type 10) and triangles
// (5) with a cell-data region array. DataArrays may be format="ascii" or
// "binary" (base64, uncompressed, UInt32 or UInt64 size header); compressed
// files and appended data are rejected with a clear error. The region array is
// the first Int-typed cell array found among: region, material, gmsh:physical,
// medit:ref, CellEntityIds; tets take its value as region and triangles as
// model face tag. Without one every tet has region 1 (triangles tag 0).
//
// Hand-written (no VTK dependency) so errors name the line and the reader
// works on memory buffers for fuzzing.
#pragma once
#include <string>
#include <string_view>

#include "mesh/tet_soup.h"

namespace polydual {

TetSoup read_vtu(std::string_view bytes, const std::string& source);
TetSoup read_vtu_file(const std::string& path);

}  // namespace polydual
