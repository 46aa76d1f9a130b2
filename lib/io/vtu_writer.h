// VTK XML UnstructuredGrid (.vtu) writer for tets: ASCII, Float64 points, Int32
// "region" cell data. Tagged triangles are written too (cell type 5, their
// tag in the same "region" array) so that the classification round-trips.
#pragma once
#include <string>

#include "mesh/tet_soup.h"

namespace polydual {

void write_vtu(const TetSoup& soup, const std::string& path);

}  // namespace polydual
