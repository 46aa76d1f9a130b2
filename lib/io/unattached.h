// Dropping the lower-dimensional input that is not attached to the tets, as
// real files carry it: Gmsh writes an element for every model entity
// (construction points such as circle centres, curves bounding no volume, the
// parts of internal sheets outside the volume) and a collapsed curve as a line
// with a repeated vertex. Such elements say nothing about the tet mesh, so they
// are dropped and counted (TetSoup::ignored) with one warning line. What is
// attached is kept whole: a triangle whose three vertices are tet vertices
// stays even when it is no face of a tet, so classify() reports it as
// non-conformal. Points are left in place (classify() drops unused vertices).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/tet_soup.h"

namespace polydual::io {

// The model entity each lower-dimensional element came from, parallel to
// soup.triangles / edges / corners; an empty vector means "the element's tag".
// declared[d]: the entities of dimension d the file declares whether or not it
// gives them elements (Gmsh msh4 $Entities), so entities with no element at
// all are counted too.
struct ElementOrigins {
  std::vector<std::int32_t> triangle, edge, corner;
  std::array<std::vector<std::int32_t>, 3> declared;
};

// Drops triangles, edges and corners with a vertex no tet uses and edges with
// a repeated vertex; adds the counts to soup.ignored and, when anything was
// dropped, one line to soup.warnings. Also drops the entity tags no longer
// carried from soup.groups (groups left empty are kept, with no entities).
void drop_unattached(TetSoup& soup, const ElementOrigins& origins = {});

// "1 point", "3 points": a count with its noun, for warnings.
std::string count_of(std::size_t n, const char* singular, const char* plural);

}  // namespace polydual::io
