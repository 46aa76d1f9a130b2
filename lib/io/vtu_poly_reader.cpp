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

// The faces stream (per cell: nFaces, then nPts ids... per face) split into
// occurrences; cell_first[c] is the first occurrence of cell c.
std::vector<Occurrence> read_occurrences(const VtkXml& f, std::size_t np, std::size_t nc,
                                         std::vector<std::size_t>& cell_first) {
  const Element& types_a = need(f, "Cells", "types");
  const auto types = f.integers(types_a);
  const Element& fo_a = need(f, "Cells", "faceoffsets");
  const auto face_offsets = f.integers(fo_a);
  const auto faces = f.integers(need(f, "Cells", "faces"));
  if (types.size() != nc || face_offsets.size() != nc)
    f.fail(types.size() != nc ? types_a.begin : fo_a.begin,
           "types has " + std::to_string(types.size()) + " and faceoffsets " + std::to_string(face_offsets.size()) +
               " values for " + std::to_string(nc) + " cells");
  std::vector<Occurrence> occ;
  cell_first.assign(nc + 1, 0);
  std::size_t k = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    const std::string place = "cell " + std::to_string(c);
    if (types[c] != kVtkPolyhedron) f.fail_at(place, "is not a VTK_POLYHEDRON (type 42)");
    cell_first[c] = occ.size();
    if (k >= faces.size()) f.fail_at(place, "faces stream ends early");
    const std::int64_t nf = faces[k++];
    if (nf < 1 || static_cast<std::size_t>(nf) > faces.size() - k) f.fail_at(place, "bad face count");
    for (std::int64_t j = 0; j < nf; ++j) {
      if (k >= faces.size()) f.fail_at(place, "faces stream ends early");
      const std::int64_t n = faces[k++];
      if (n < 3 || static_cast<std::size_t>(n) > faces.size() - k)
        f.fail_at(place, "face " + std::to_string(j) + " has a bad point count");
      Occurrence o{CellId(c), {}};
      o.loop.reserve(static_cast<std::size_t>(n));
      for (std::int64_t v = 0; v < n; ++v, ++k) {
        if (faces[k] < 0 || static_cast<std::size_t>(faces[k]) >= np) f.fail_at(place, "face point index out of range");
        o.loop.emplace_back(static_cast<std::uint32_t>(faces[k]));
      }
      occ.push_back(std::move(o));
    }
    if (static_cast<std::int64_t>(k) != face_offsets[c]) f.fail_at(place, "faceoffsets disagrees with the faces stream");
  }
  if (k != faces.size()) f.fail_at("faces", "the stream has " + std::to_string(faces.size() - k) + " values after the last cell");
  cell_first[nc] = occ.size();
  return occ;
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


// Pairs occurrences into faces: an open (unpaired) face waits under its
// canonical loop for an occurrence in the opposite sense. Returns the
// half-face of every occurrence.
std::vector<HalfFace> pair_faces(const VtkXml& f, const std::vector<Occurrence>& occ, PolyMesh& mesh) {
  // Per-occurrence face classification (see vtu_poly_writer.h).
  const bool classified = f.find_array("FieldData", "face_kind") != nullptr;
  const auto kinds = optional_ints(f, "FieldData", "face_kind", occ.size(), -1, 0, static_cast<int>(FaceKind::Fracture));
  const auto tags = optional_ints(f, "FieldData", "face_tag", occ.size(), 0, kInt32Min, kInt32Max);
  struct Open { FaceId face; bool reversed; };
  std::map<std::vector<std::uint32_t>, std::vector<Open>> open;
  std::vector<HalfFace> half(occ.size());
  for (std::size_t o = 0; o < occ.size(); ++o) {
    CanonicalLoop c = canonical(occ[o].loop);
    auto& waiting = open[c.key];
    auto it = std::find_if(waiting.begin(), waiting.end(), [&](const Open& w) { return w.reversed != c.reversed; });
    if (it != waiting.end()) {
      mesh.face_neighbour[it->face.idx] = occ[o].cell;
      half[o] = HalfFace(it->face, 1);
      if (classified && (kinds[o] != static_cast<std::int64_t>(mesh.face_kind[it->face.idx]) ||
                         tags[o] != mesh.face_tag[it->face.idx]))
        f.fail_at("cell " + std::to_string(occ[o].cell.idx), "the two sides of a face disagree on its kind or tag");
      waiting.erase(it);
      continue;
    }
    const FaceKind kind = classified ? static_cast<FaceKind>(kinds[o]) : FaceKind::Interior;
    const FaceId face = mesh.add_face(occ[o].loop, occ[o].cell, CellId::invalid(), kind, static_cast<std::int32_t>(tags[o]));
    half[o] = HalfFace(face, 0);
    waiting.push_back({face, c.reversed});
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
  const std::vector<Occurrence> occ = read_occurrences(file, np, nc, cell_first);
  const auto material = optional_ints(file, "CellData", "material", nc, 0, kInt32Min, kInt32Max);
  const auto primal = optional_ints(file, "CellData", "primal_vertex", nc, -1, -1, kInt32Max);
  const std::vector<HalfFace> half = pair_faces(file, occ, mesh);
  for (std::size_t c = 0; c < nc; ++c)
    mesh.add_cell(std::span<const HalfFace>(half.data() + cell_first[c], half.data() + cell_first[c + 1]),
                  static_cast<std::int32_t>(material[c]),
                  primal[c] < 0 ? VertexId::invalid() : VertexId(static_cast<std::uint32_t>(primal[c])));
  return mesh;
}

PolyMesh read_vtu_poly(const std::string& path) { return read_vtu_poly_bytes(io::read_file_bytes(path), path); }

}  // namespace polydual
