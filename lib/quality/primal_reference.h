// The reference validate() checks a mixed dual against (mesh/validate.h),
// from a PrimalMesh: here rather than in lib/mesh because whether a model
// face is planar is a sign decision (lib/predicates).
#pragma once
#include "mesh/primal_mesh.h"
#include "mesh/validate.h"

namespace polydual {

// Model vertices (class dim 0) at their places; (edge tag, vertex tag) for
// each primal edge on a model edge with an end on a model vertex; every
// model tag of the vertices, edges and faces, increasing; per region the
// sum of its cells' volumes (each cell cut into fans of tets from its vertex
// mean over its faces' fans from their vertex means, double: a hexahedron
// with warped faces has no volume of its own, but the fans of a face shared
// by two cells are the same from both sides, so a material's volume is that
// of its boundary's fans); the regions bounded (external or interface) by a
// model face that is not planar (EXACT: orient3d of every vertex of the model
// face against the first three vertices of its first face).
PrimalReference primal_reference(const PrimalMesh& m);

}  // namespace polydual
