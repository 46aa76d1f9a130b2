// Gmsh .msh 2.2 and 4.1 reader, ASCII and binary (SPEC §2).
//
// Written by hand rather than through libgmsh because (1) errors must name the
// exact line or byte, (2) the fuzzers need a memory-buffer API, and (3) libgmsh
// keeps global state (gmsh::initialize, a current model) that would make
// readers non-reentrant.
//
// What becomes what: linear tets (type 4) -> tets; triangles (2), lines (1)
// and points (15) -> tagged triangles / edges / corners. msh4: tet region = the
// volume entity's first physical tag, else its entity tag; triangle / edge /
// corner tag = the surface / curve / point entity tag; full_classification is
// set when $Entities is present and triangles were given. msh2: every tag is
// the physical tag if nonzero, else the elementary tag. Other 3D element types
// are errors (only linear tets are supported); other lower-dimensional types
// are ignored.
#pragma once
#include <string>
#include <string_view>

#include "mesh/tet_soup.h"

namespace polydual {

// Parses a whole .msh file held in memory; `source` names it in errors.
TetSoup read_msh(std::string_view bytes, const std::string& source);
TetSoup read_msh_file(const std::string& path);

}  // namespace polydual
