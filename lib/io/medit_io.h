// Medit .mesh (ASCII), the format CGAL Mesh_3 writes: Vertices "x y z ref",
// Tetrahedra "a b c d ref" (ref -> region), Triangles "a b c ref" (ref -> model
// face tag), Edges "a b ref", Corners "i" (tag = the vertex's 1-based index,
// since Medit corners carry no tag of their own). Indices are 1-based.
// CGAL Mesh_3's two conventions (output_to_medit) are both read:
// show_patches = true writes each triangle once with its surface patch as ref;
// show_patches = false (the default) writes every triangle twice, once per
// side with a subdomain as ref (both sides' on an interface, the inner one
// twice on the boundary): such pairs are merged into one triangle tagged by
// its pair of subdomains (1, 2, ... in increasing pair order; soup.groups
// names them "subdomains a|b" or "subdomains a|outside"; a warning says so).
// Lower-dimensional elements not attached to the tets are dropped
// (io/unattached.h).
#pragma once
#include <string>
#include <string_view>

#include "mesh/tet_soup.h"

namespace polydual {

TetSoup read_medit(std::string_view bytes, const std::string& source);
TetSoup read_medit_file(const std::string& path);
// Writes Vertices (ref 0), Tetrahedra, Triangles, Edges and Corners.
void write_medit(const TetSoup& soup, const std::string& path);

}  // namespace polydual
