// VTK XML UnstructuredGrid (.vtu, version 1.0) writer for PolyMesh (design §9):
// one VTK_POLYHEDRON cell per dual cell, opens in ParaView and is read back
// exactly by read_vtu_poly (lib/io/vtu_poly_reader.h), in every format of
// VtuOptions (ascii, inline base64, appended raw; zlib-compressed or not).
//
// File contents:
//   CellData   material (Int32), primal_vertex (Int64, -1 when none), then the
//              caller's extra arrays (e.g. "valid", "bad_tets") in the given order;
//   PointData  class_dim (Int8), class_tag (Int32): each point's model entity;
//   Cells      connectivity/offsets (the cell's distinct points, first-seen order),
//              types (42), faces/faceoffsets (per cell: nFaces, then nPts ids...,
//              each face in the cell's outward orientation);
//   FieldData  face_kind, face_tag (Int32): one entry per (cell, local face) in
//              faces-stream order, because VTK has no face attributes and the
//              reader needs the model classification of every face.
#pragma once
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "io/model_names.h"
#include "mesh/poly_mesh.h"

namespace polydual {

// A caller-supplied cell array, one value per cell.
struct CellField {
  std::string name;
  std::variant<std::vector<double>, std::vector<std::int32_t>> values;  // Float64 or Int32
};

struct VtuOptions {
  // false: every array as ASCII text (doubles with 17 significant digits);
  // true: "binary" = base64 of the raw little-endian bytes inside each
  // DataArray, about half the size and faster to parse.
  bool binary = false;
  // true: the raw bytes of every array in one <AppendedData encoding="raw">
  // section after the XML (VTK's own default; the fastest to write and read,
  // about 3/4 of the "binary" size). Overrides `binary`.
  bool appended = false;
  // 0: no compression; 1..9: every binary or appended array zlib-compressed at
  // this level in 32 KiB blocks (compressor="vtkZLibDataCompressor", what
  // meshio writes). Needs binary or appended.
  int zlib_level = 0;
};

// Writes `mesh` to `path` atomically (no half-written file on failure).
// Same mesh and options -> same bytes. Throws UsageError when an extra field's
// size differs from the cell count or its name clashes with a built-in array,
// or when the options ask for compressed ASCII or a level outside 0..9.
// With `names`, FieldData also holds region_name_tag (Int32) and region_name
// (String), face_name_tag and face_name: each named region / model face's tag
// and name; nothing is added without names.
void write_vtu_poly(const PolyMesh& mesh, const std::string& path,
                    const std::vector<CellField>& extra = {}, const VtuOptions& options = {},
                    const ModelNames& names = {});

}  // namespace polydual
