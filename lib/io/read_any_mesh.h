// Reading a mesh of any cell type: what read_tet_mesh reads, and a surface
// mesh (triangles and quadrangles, no volume cell) where the format carries
// one (Gmsh .msh). Mixed volume meshes (pyramids, prisms, hexahedra) come
// through read_tet_mesh as well, in TetSoup::other_cells.
#pragma once
#include <string>

#include "mesh/tet_soup.h"

namespace polydual {

// Same errors as read_tet_mesh, but for a .msh file that holds surface
// elements and no volume cell, which it reads as a surface mesh.
TetSoup read_any_mesh(const std::string& path);

}  // namespace polydual
