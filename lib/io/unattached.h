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
#include <string>
#include <string_view>
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

// Gmsh's homology and cohomology solver (`Homology`, `Cohomology` in a .geo)
// adds each basis chain to the mesh as a new discrete entity (points, lines,
// triangles or tets on the mesh's own nodes) in a physical group of its own,
// named "H_<dim>{domain}..." for homology and "H^<dim>{domain}..." for
// cohomology. They are results computed on the mesh, not model entities: read
// as curves they contradict the model's faces, read as tets they overlap the
// mesh. True for such a name ("H_" or "H^" then a dimension digit).
bool is_chain_name(std::string_view name);

// The elements of one entity that the reader appended consecutively:
// [begin, end) of soup.tets / triangles / edges / corners for dim 3 / 2 / 1 /
// 0, with the physical group they were read in.
struct ElementRun {
  int dim = 0;
  std::int32_t entity = 0;
  std::int32_t group = 0;
  std::size_t begin = 0, end = 0;
};

// Drops the elements of `chains` (runs of chain groups, in increasing order
// of begin per dimension; their origins alongside), and the chain groups from
// soup.groups; counts them in soup.ignored (their entities as points, curves
// or surfaces, every element, the groups as chains) with one warning line
// naming the groups. Call before drop_unattached.
void drop_chains(TetSoup& soup, ElementOrigins& origins, const std::vector<ElementRun>& chains);

// "1 point", "3 points": a count with its noun, for warnings.
std::string count_of(std::size_t n, const char* singular, const char* plural);

}  // namespace polydual::io
