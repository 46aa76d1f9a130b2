// Writing a TetSoup by file extension (the format registry, io/format_registry.h),
// for round trips and conversions:
// .msh (Gmsh 4.1 ASCII with $Entities), .mesh (Medit), .node/.ele (TetGen),
// .vtu (VTK XML ASCII). Every writer goes through write_file_atomically.
#pragma once
#include <string>

#include "mesh/tet_soup.h"

namespace polydual {

// Throws UsageError for an unsupported extension, std::runtime_error when the
// file cannot be written.
void write_tet_mesh(const TetSoup& soup, const std::string& path);

}  // namespace polydual
