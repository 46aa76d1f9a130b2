// Gmsh .msh 2.2 and 4.1 reader, ASCII and binary (design §2); 2.0 and 2.1 are
// read as 2.2, the version however spelt ("2", "2.0", Netgen's "2.000000").
//
// Written by hand rather than through libgmsh because (1) errors must name the
// exact line or byte, (2) the fuzzers need a memory-buffer API, and (3) libgmsh
// keeps global state (gmsh::initialize, a current model) that would make
// readers non-reentrant.
//
// What becomes what: tets (type 4, and high-order tets by their first four,
// corner, nodes) -> tets; triangles, lines and points (linear or high-order,
// by their corners) -> tagged triangles / edges / corners. msh4: tet region =
// the volume entity's first physical tag, else its entity tag; triangle / edge
// / corner tag = the surface / curve / point entity tag; partition pieces of
// $PartitionedEntities are mapped to their parent model entity (elements on
// partition boundaries and ghost elements are dropped, repeated nodes with the
// same coordinates merged); full_classification is set when $Entities gives
// elements for all its curves (but collapsed ones), surfaces and volumes (a
// file saved with -save_all, or whose every entity is in a physical group).
// msh2: every tag is the physical tag if nonzero, else the elementary tag.
// Both: $PhysicalNames and the physical tags become soup.groups; homology and
// cohomology chains that Gmsh added to the mesh, and input not attached to the
// volume cells, are dropped (io/unattached.h); other 3D element types are errors;
// other lower-dimensional types are ignored.
#pragma once
#include <string>
#include <string_view>

#include "mesh/tet_soup.h"

namespace polydual {

// Parses a whole .msh file held in memory; `source` names it in errors.
// With `surfaces`, a file with no volume cell is read as a surface mesh (its
// triangles and quads); otherwise it holds no tetrahedra (an error).
TetSoup read_msh(std::string_view bytes, const std::string& source, bool surfaces = false);
TetSoup read_msh_file(const std::string& path, bool surfaces = false);

}  // namespace polydual
