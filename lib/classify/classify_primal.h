// build_primal: a mixed cell soup -> PrimalMesh (design §14), the validation
// classify() does for tets made for any cell type: every volume cell
// positively oriented (EXACT: orient3d on each of its corner tets,
// mesh/cell_types.h), then the conformity checks and the classification of
// PrimalMeshBuilder.
#pragma once
#include <string>
#include <vector>

#include "mesh/cell_soup.h"
#include "mesh/primal_mesh.h"

namespace polydual {

// A type whose every cell is inverted (all corner tets negative: the file
// follows the mirror convention, as VTK's wedge against Gmsh's prism) is
// mirrored whole, with a warning in `warnings` naming the type. Otherwise a
// cell with a corner tet that is not positive is an InputError naming it
// ("prism 12 is inverted" or "... is degenerate or twisted at its corner k").
PrimalMesh build_primal(CellSoup soup, std::vector<std::string>* warnings = nullptr);

}  // namespace polydual
