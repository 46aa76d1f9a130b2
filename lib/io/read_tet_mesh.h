// Reading any supported tet mesh by file extension, through the format
// registry (io/format_registry.h): .msh (Gmsh 2.0-2.2/4.1;
// .gmsh2, Netgen's name for its msh 2.0 export, too),
// .mesh (Medit), .node/.ele (TetGen, with .face when present), .vtu (VTK XML).
#pragma once
#include <string>

#include "mesh/tet_soup.h"

namespace polydual {

// Throws InputError(path, "", reason) when the path is not a readable regular
// file (io/file_bytes.h: "cannot open file (...)", "is a directory; ...", "is
// a dangling symbolic link (to 'T')"), InputError naming the extension when
// it is not supported, and the reader's InputError (with line or byte) when
// the content is bad.
TetSoup read_tet_mesh(const std::string& path);

}  // namespace polydual
