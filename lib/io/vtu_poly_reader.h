// Reads a .vtu written by write_vtu_poly (ASCII or uncompressed binary) back
// into a PolyMesh.
//
// VTK stores each polyhedron's faces separately, so shared faces are rebuilt:
// two face occurrences (in any cells, possibly the same one) whose loops are the
// same cyclic sequence read in opposite senses become one face; the first cell
// (in file order) to list it is the owner and the loop is kept as that cell sees
// it. An occurrence left unmatched is a boundary face. Faces are numbered in
// order of first occurrence, so face ids may differ from the written mesh while
// the topology (and every point, bit for bit) is the same.
// A face listed twice by one cell in opposite senses comes back as a slit face
// (owner == neighbour).
//
// Optional arrays (material, primal_vertex, class_dim, class_tag, face_kind,
// face_tag) default to 0 / invalid / unclassified / inferred kinds when absent.
// Errors: InputError(path, "line N" or "cell N", what).
#pragma once
#include <string>

#include "mesh/poly_mesh.h"

namespace polydual {

PolyMesh read_vtu_poly(const std::string& path);

}  // namespace polydual
