// Reads a .vtu of VTK_POLYHEDRON cells (as write_vtu_poly writes them, in any
// of its formats, or as VTK writes them: ascii, inline base64, appended raw or
// base64, zlib-compressed; lib/io/vtk_xml.h) back into a PolyMesh.
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
// Every Cells array is read and checked against the others, since VTK and
// ParaView read a cell from some of them only: connectivity (point ids in
// range), offsets (one per cell, non-decreasing, the last equal to the
// connectivity's size), types (every cell 42, VTK_POLYHEDRON), faces (per
// cell a face count >= 1, then per face a point count >= 3 and its point ids
// in range) and faceoffsets (one per cell, the end of its record in faces),
// and each cell's points in connectivity are exactly the points of its faces,
// each listed once.
// Optional arrays (material, primal_vertex, class_dim, class_tag, face_kind,
// face_tag) default to 0 / invalid / unclassified / inferred kinds when absent.
// Errors: InputError(path, "line N", "byte N" or "cell N", what), `what`
// naming the DataArray; values out of range of their field (class_dim outside
// -1..3, tags beyond 32 bits, face kinds other than 0..3) are errors too.
#pragma once
#include <string>
#include <string_view>

#include "mesh/poly_mesh.h"

namespace polydual {

PolyMesh read_vtu_poly(const std::string& path);
// The same from the bytes of a file; `source` names it in errors.
PolyMesh read_vtu_poly_bytes(std::string_view bytes, const std::string& source);

}  // namespace polydual
