#include "io/vtu_poly_reader.h"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <string_view>

#include "core/error.h"
#include "io/file_bytes.h"
#include "io/vtk_xml.h"

namespace polydual {
namespace {

using io::vtkxml::Element;
using io::vtkxml::VtkXml;

constexpr std::int64_t kVtkPolyhedron = 42;
constexpr std::int64_t kInt32Min = std::numeric_limits<std::int32_t>::min();
constexpr std::int64_t kInt32Max = std::numeric_limits<std::int32_t>::max();

const Element& need(const VtkXml& f, std::string_view section, std::string_view name) {
  if (const Element* a = f.find_array(section, name)) return *a;
  f.fail_at(std::string(section), "missing DataArray '" + std::string(name) + "'");
}

// The values of an optional array (`fallback` repeated when absent), checked
// to hold `expected` values in [lo, hi].
std::vector<std::int64_t> optional_ints(const VtkXml& f, std::string_view section, std::string_view name,
                                        std::size_t expected, std::int64_t fallback, std::int64_t lo, std::int64_t hi) {
  const Element* a = f.find_array(section, name);
  if (!a) return std::vector<std::int64_t>(expected, fallback);
  std::vector<std::int64_t> v = f.integers_in(*a, lo, hi);
  if (v.size() != expected)
    f.fail(a->begin, "DataArray '" + std::string(name) + "' has " + std::to_string(v.size()) + " values, expected " +
                         std::to_string(expected));
  return v;
}

// Points with their model classification (class_dim, class_tag).
void read_points(const VtkXml& f, std::size_t np, PolyMesh& mesh) {
  const Element* pts = f.find_array("Points");
  if (!pts && np > 0) f.fail_at("Points", "missing");
  const std::vector<double> xyz = pts ? f.reals(*pts) : std::vector<double>{};
  if (xyz.size() != 3 * np)
    f.fail(pts->begin, "DataArray '" + f.array_name(*pts) + "' has " + std::to_string(xyz.size()) +
                           " values, expected " + std::to_string(3 * np));
  const auto cdim = optional_ints(f, "PointData", "class_dim", np, ModelRef::kNone, ModelRef::kNone, 3);
  const auto ctag = optional_ints(f, "PointData", "class_tag", np, 0, kInt32Min, kInt32Max);
  for (std::size_t i = 0; i < np; ++i)
    mesh.add_point({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]},
                   ModelRef{static_cast<std::int8_t>(cdim[i]), static_cast<std::int32_t>(ctag[i])});
}

// One cell's listing of one face, in the cell's outward orientation.
struct Occurrence {
  CellId cell;
  std::vector<PointId> loop;
};

// The Cells section's point lists: cell c's points are connectivity[offsets[c-1]
// .. offsets[c]) (offsets[-1] = 0), VTK's end-offset convention.
struct CellPointLists {
  std::vector<std::int64_t> connectivity, offsets;
  std::size_t begin(std::size_t c) const { return c == 0 ? 0 : static_cast<std::size_t>(offsets[c - 1]); }
  std::size_t end(std::size_t c) const { return static_cast<std::size_t>(offsets[c]); }
};

[[noreturn]] void fail_cell(const VtkXml& f, std::size_t c, std::string_view array, const std::string& what) {
  f.fail_at("cell " + std::to_string(c), "DataArray '" + std::string(array) + "': " + what);
}

// One value per cell, else an error at the array naming both counts.
void require_per_cell(const VtkXml& f, const Element& a, std::size_t values, std::size_t nc) {
  if (values != nc)
    f.fail(a.begin, "DataArray '" + f.array_name(a) + "' has " + std::to_string(values) + " values for " +
                        std::to_string(nc) + " cells (NumberOfCells)");
}

// connectivity (every id a point), offsets (one per cell, non-decreasing, the
// last the connectivity's size) and types (every cell a VTK_POLYHEDRON):
// what VTK itself reads a cell's points and type from, so they must agree
// with the faces stream (check_cell_points) or ParaView shows another mesh.
CellPointLists read_cell_point_lists(const VtkXml& f, std::size_t np, std::size_t nc) {
  CellPointLists l;
  const Element& conn_a = need(f, "Cells", "connectivity");
  const Element& off_a = need(f, "Cells", "offsets");
  const Element& types_a = need(f, "Cells", "types");
  l.connectivity = f.integers(conn_a);
  l.offsets = f.integers(off_a);
  const std::vector<std::int64_t> types = f.integers(types_a);
  require_per_cell(f, off_a, l.offsets.size(), nc);
  require_per_cell(f, types_a, types.size(), nc);
  const auto nconn = static_cast<std::int64_t>(l.connectivity.size());
  std::int64_t prev = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    const std::int64_t o = l.offsets[c];
    if (o < prev)
      fail_cell(f, c, "offsets", "value " + std::to_string(o) + " is below the previous cell's end " +
                                     std::to_string(prev) + " (offsets must not decrease)");
    if (o > nconn)
      fail_cell(f, c, "offsets", "value " + std::to_string(o) + " is beyond the end of 'connectivity' (" +
                                     std::to_string(nconn) + " values)");
    if (types[c] != kVtkPolyhedron)
      fail_cell(f, c, "types", "type " + std::to_string(types[c]) + " is not a VTK_POLYHEDRON (42)");
    for (std::int64_t k = prev; k < o; ++k)
      if (l.connectivity[k] < 0 || l.connectivity[k] >= static_cast<std::int64_t>(np))
        fail_cell(f, c, "connectivity", "point id " + std::to_string(l.connectivity[k]) + " at index " +
                                            std::to_string(k) + " out of range (" + std::to_string(np) + " points)");
    prev = o;
  }
  if (prev != nconn)
    f.fail(off_a.begin, "DataArray 'offsets': the last cell ends at " + std::to_string(prev) + " but 'connectivity' has " +
                            std::to_string(nconn) + " values");
  return l;
}

// One face of cell c from the faces stream at k (its point count, then its
// point ids), k advanced past it.
Occurrence read_face(const VtkXml& f, const std::vector<std::int64_t>& faces, std::size_t& k, std::size_t c,
                     std::int64_t j, std::size_t np) {
  const std::string face = "face " + std::to_string(j) + " ";
  if (k >= faces.size()) fail_cell(f, c, "faces", face + "is missing: the stream ends early");
  const std::int64_t n = faces[k++];
  if (n < 3) fail_cell(f, c, "faces", face + "has " + std::to_string(n) + " points (at least 3)");
  if (static_cast<std::size_t>(n) > faces.size() - k)
    fail_cell(f, c, "faces", face + "has " + std::to_string(n) + " points but the stream ends after " +
                                 std::to_string(faces.size() - k));
  Occurrence o{CellId(c), {}};
  o.loop.reserve(static_cast<std::size_t>(n));
  for (std::int64_t v = 0; v < n; ++v, ++k) {
    if (faces[k] < 0 || static_cast<std::size_t>(faces[k]) >= np)
      fail_cell(f, c, "faces", face + "point id " + std::to_string(faces[k]) + " at index " + std::to_string(k) +
                                   " out of range (" + std::to_string(np) + " points)");
    o.loop.emplace_back(static_cast<std::uint32_t>(faces[k]));
  }
  return o;
}

// The faces stream (per cell: nFaces, then nPts ids... per face; faceoffsets
// holds the end of each cell's record) split into occurrences; cell_first[c]
// is the first occurrence of cell c.
std::vector<Occurrence> read_occurrences(const VtkXml& f, std::size_t np, std::size_t nc,
                                         std::vector<std::size_t>& cell_first) {
  const Element& fo_a = need(f, "Cells", "faceoffsets");
  const auto face_offsets = f.integers(fo_a);
  const auto faces = f.integers(need(f, "Cells", "faces"));
  require_per_cell(f, fo_a, face_offsets.size(), nc);
  std::vector<Occurrence> occ;
  cell_first.assign(nc + 1, 0);
  std::size_t k = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    cell_first[c] = occ.size();
    if (k >= faces.size()) fail_cell(f, c, "faces", "the stream ends before the cell's record");
    const std::int64_t nf = faces[k++];
    if (nf < 1 || static_cast<std::size_t>(nf) > faces.size() - k)
      fail_cell(f, c, "faces", "face count " + std::to_string(nf) + " at index " + std::to_string(k - 1) +
                                   (nf < 1 ? " (at least 1)" : " exceeds the values left in the stream"));
    for (std::int64_t j = 0; j < nf; ++j) occ.push_back(read_face(f, faces, k, c, j, np));
    if (static_cast<std::int64_t>(k) != face_offsets[c])
      fail_cell(f, c, "faceoffsets", "value " + std::to_string(face_offsets[c]) + " but the cell's record in 'faces' ends at " +
                                         std::to_string(k));
  }
  if (k != faces.size())
    f.fail_at("faces", "the stream has " + std::to_string(faces.size() - k) + " values after the last cell");
  cell_first[nc] = occ.size();
  return occ;
}

// Per cell, its points in connectivity are exactly the points of its faces,
// each listed once. mark[p] is g when p is on one of the current cell's
// faces and g + 1 once connectivity listed it too (g grows by 2 per cell;
// the marks are cleared when it would wrap).
void check_cell_points(const VtkXml& f, const CellPointLists& l, const std::vector<Occurrence>& occ,
                       const std::vector<std::size_t>& cell_first, std::size_t np) {
  std::vector<std::uint32_t> mark(np, 0);
  std::uint32_t g = 1;
  for (std::size_t c = 0; c + 1 < cell_first.size(); ++c, g += 2) {
    if (g >= std::numeric_limits<std::uint32_t>::max() - 2) {
      std::fill(mark.begin(), mark.end(), 0);
      g = 1;
    }
    std::size_t on_faces = 0;
    for (std::size_t o = cell_first[c]; o < cell_first[c + 1]; ++o)
      for (PointId p : occ[o].loop)
        if (mark[p.idx] != g) {
          mark[p.idx] = g;
          ++on_faces;
        }
    for (std::size_t k = l.begin(c); k < l.end(c); ++k) {
      const auto p = static_cast<std::size_t>(l.connectivity[k]);
      if (mark[p] != g)
        fail_cell(f, c, "connectivity", "point " + std::to_string(p) +
                                            (mark[p] == g + 1 ? " is listed twice" : " is on none of the cell's faces"));
      mark[p] = g + 1;
    }
    if (l.end(c) - l.begin(c) == on_faces) continue;
    for (std::size_t o = cell_first[c]; o < cell_first[c + 1]; ++o)
      for (PointId p : occ[o].loop)
        if (mark[p.idx] == g)
          fail_cell(f, c, "connectivity", "point " + std::to_string(p.idx) + " of the cell's faces is missing");
  }
}

// A face loop up to rotation: its lexicographically smallest rotation over both
// reading directions (all starts, since a loop may repeat a point, e.g. a cap
// through a model-edge midpoint twice). `reversed` tells which direction won,
// so the two sides of one face get the same key and opposite flags.
struct CanonicalLoop {
  std::vector<std::uint32_t> key;
  bool reversed = false;
};
CanonicalLoop canonical(const std::vector<PointId>& loop) {
  const std::size_t n = loop.size();
  const PointId lowest = *std::min_element(loop.begin(), loop.end());
  CanonicalLoop best;
  std::vector<std::uint32_t> candidate(n);
  for (bool reversed : {false, true})
    for (std::size_t m = 0; m < n; ++m) {
      if (loop[m] != lowest) continue;
      for (std::size_t k = 0; k < n; ++k)
        candidate[k] = loop[reversed ? (m + n - k) % n : (m + k) % n].idx;
      if (best.key.empty() || candidate < best.key) best = {candidate, reversed};
    }
  return best;
}


// "face (points 4 9 7 ...)" for errors.
std::string face_points(const std::vector<PointId>& loop) {
  std::string s = "face (points";
  for (std::size_t k = 0; k < loop.size() && k < 8; ++k) {
    s += ' ';
    s += std::to_string(loop[k].idx);
  }
  s += loop.size() > 8 ? " ...)" : ")";
  return s;
}

// Pairs occurrences into faces: a face is listed at most twice, in opposite
// senses (by its two cells, or by one cell on both sides of a slit); a third
// listing (a face of three cells: non-manifold) or a second in the same
// sense (two cells on one side of it) is an error. An occurrence left alone
// is a boundary face. Returns the half-face of every occurrence.
std::vector<HalfFace> pair_faces(const VtkXml& f, const std::vector<Occurrence>& occ, PolyMesh& mesh) {
  // Per-occurrence face classification (see vtu_poly_writer.h).
  const bool classified = f.find_array("FieldData", "face_kind") != nullptr;
  const auto kinds = optional_ints(f, "FieldData", "face_kind", occ.size(), -1, 0, static_cast<int>(FaceKind::Fracture));
  const auto tags = optional_ints(f, "FieldData", "face_tag", occ.size(), 0, kInt32Min, kInt32Max);
  struct Slot { FaceId face; bool reversed; bool paired; };
  std::map<std::vector<std::uint32_t>, Slot> slots;  // by canonical loop
  std::vector<HalfFace> half(occ.size());
  for (std::size_t o = 0; o < occ.size(); ++o) {
    CanonicalLoop c = canonical(occ[o].loop);
    const auto [it, fresh] = slots.try_emplace(std::move(c.key), Slot{FaceId::invalid(), c.reversed, false});
    Slot& slot = it->second;
    if (fresh) {
      const FaceKind kind = classified ? static_cast<FaceKind>(kinds[o]) : FaceKind::Interior;
      slot.face = mesh.add_face(occ[o].loop, occ[o].cell, CellId::invalid(), kind, static_cast<std::int32_t>(tags[o]));
      half[o] = HalfFace(slot.face, 0);
      continue;
    }
    const std::size_t cell = occ[o].cell.idx, owner = mesh.face_owner[slot.face.idx].idx;
    if (slot.paired)
      fail_cell(f, cell, "faces", face_points(occ[o].loop) + " is already shared by cells " + std::to_string(owner) +
                                      " and " + std::to_string(mesh.face_neighbour[slot.face.idx].idx) +
                                      ": a face of three cells (non-manifold)");
    if (slot.reversed == c.reversed)
      fail_cell(f, cell, "faces", face_points(occ[o].loop) + " is listed in the same sense by cell " +
                                      std::to_string(owner) + ": two cells on one side of a face");
    mesh.face_neighbour[slot.face.idx] = occ[o].cell;
    half[o] = HalfFace(slot.face, 1);
    slot.paired = true;
    if (classified && (kinds[o] != static_cast<std::int64_t>(mesh.face_kind[slot.face.idx]) ||
                       tags[o] != mesh.face_tag[slot.face.idx]))
      f.fail_at("cell " + std::to_string(cell), "the two sides of a face disagree on its kind or tag");
  }
  if (!classified)  // no classification stored: an unpaired face lies on the boundary
    for (std::size_t i = 0; i < mesh.num_faces(); ++i)
      if (!mesh.face_neighbour[i].valid()) mesh.face_kind[i] = FaceKind::External;
  return half;
}

}  // namespace

PolyMesh read_vtu_poly_bytes(std::string_view bytes, const std::string& source) {
  const VtkXml file(bytes, source, "UnstructuredGrid");
  const Element& piece = file.piece();
  const auto np = static_cast<std::size_t>(file.count_attr(piece, "NumberOfPoints"));
  const auto nc = static_cast<std::size_t>(file.count_attr(piece, "NumberOfCells"));
  PolyMesh mesh;
  read_points(file, np, mesh);
  std::vector<std::size_t> cell_first;
  std::vector<Occurrence> occ;
  {
    const CellPointLists lists = read_cell_point_lists(file, np, nc);
    occ = read_occurrences(file, np, nc, cell_first);
    check_cell_points(file, lists, occ, cell_first, np);
  }
  const auto material = optional_ints(file, "CellData", "material", nc, 0, kInt32Min, kInt32Max);
  const auto primal = optional_ints(file, "CellData", "primal_vertex", nc, -1, -1, kInt32Max);
  const std::vector<HalfFace> half = pair_faces(file, occ, mesh);
  for (std::size_t c = 0; c < nc; ++c)
    mesh.add_cell(std::span<const HalfFace>(half.data() + cell_first[c], half.data() + cell_first[c + 1]),
                  static_cast<std::int32_t>(material[c]),
                  primal[c] < 0 ? VertexId::invalid() : VertexId(static_cast<std::uint32_t>(primal[c])));
  return mesh;
}

// The head, the NUL-free text and the closing tag are checked as the file
// loads (load_vtk_xml), so a zero-filled or cut file is refused early.
PolyMesh read_vtu_poly(const std::string& path) {
  io::InputFile file(path);
  return read_vtu_poly_bytes(io::vtkxml::load_vtk_xml(file), path);
}

}  // namespace polydual
