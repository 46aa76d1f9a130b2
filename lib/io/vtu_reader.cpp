#include "io/vtu_reader.h"

#include <algorithm>

#include <array>
#include <limits>
#include <vector>

#include "io/file_bytes.h"
#include "io/record_checks.h"
#include "io/vtk_xml.h"

namespace polydual {
namespace {

using io::vtkxml::Element;
using io::vtkxml::VtkXml;

// Cell-data arrays taken as the region, in this order of preference: ours and
// the common names first, then those meshio writes for Gmsh, Medit and
// DOLFIN/XDMF meshes.
constexpr std::string_view kRegionNames[] = {"region", "material", "gmsh:physical", "medit:ref", "CellEntityIds"};

constexpr std::int64_t kVertex = 1, kLine = 3, kTriangle = 5, kQuad = 9, kTetra = 10, kHex = 12, kWedge = 13,
                       kPyramid = 14;

// Node count of a VTK cell type that is read, else -1.
std::int64_t nodes_of(std::int64_t type) {
  switch (type) {
    case kVertex: return 1;
    case kLine: return 2;
    case kTriangle: return 3;
    case kQuad: case kTetra: return 4;
    case kPyramid: return 5;
    case kWedge: return 6;
    case kHex: return 8;
    default: return -1;
  }
}

// A cell of a volume type other than the tet, or a quad, into the soup. VTK's
// wedge is the mirror image of Gmsh's prism (its (0, 1, 2) points away from
// (3, 4, 5)): reordered to mesh/cell_types.h's; the others share its order.
void add_other(TetSoup& soup, std::int64_t type, const std::array<std::uint32_t, 8>& v, std::int32_t tag,
               std::int64_t c) {
  if (type == kQuad) return soup.quads.push_back({{v[0], v[1], v[2], v[3]}, tag});
  SoupCell cell{type == kHex ? CellType::Hex : type == kWedge ? CellType::Prism : CellType::Pyramid, v, tag,
                std::uint64_t(c + 1)};
  if (type == kWedge) cell.v = {v[0], v[2], v[1], v[3], v[5], v[4], 0, 0};
  soup.other_cells.push_back(cell);
}

// The arrays of the Piece the tet mesh is built from.
struct Arrays {
  std::int64_t npoints = 0, ncells = 0;
  std::vector<double> xyz;
  std::vector<std::int64_t> conn, offsets, types, region;
  bool has_region = false;
  std::size_t piece_pos = 0, conn_pos = 0, off_pos = 0, types_pos = 0;
};

const Element& need_cells_array(const VtkXml& f, const Element& piece, std::string_view name) {
  const Element* a = f.find_array("Cells", name);
  if (!a) f.fail(piece.begin, "Cells need connectivity, offsets and types arrays");
  return *a;
}

Arrays read_arrays(const VtkXml& f) {
  Arrays r;
  const auto& all = f.elements();
  if (std::none_of(all.begin(), all.end(), [](const Element& e) { return e.name == "Piece"; }))
    f.fail(0, "the file holds no tetrahedra (no <Piece> in the UnstructuredGrid)");
  const Element& piece = f.piece();
  r.piece_pos = piece.begin;
  r.npoints = f.count_attr(piece, "NumberOfPoints");
  r.ncells = f.count_attr(piece, "NumberOfCells");
  const Element* points = f.find_array("Points");
  if (!points) f.fail(piece.begin, "Piece has no Points");
  if (io::vtkxml::scalar_is_integer(f.array_type(*points)) || f.components(*points) != 3)
    f.fail(points->begin, "Points must be a Float32/Float64 array of 3 components");
  r.xyz = f.reals(*points);
  if (static_cast<std::int64_t>(r.xyz.size()) != 3 * r.npoints)
    f.fail(piece.begin, "NumberOfPoints is " + std::to_string(r.npoints) + " but Points holds " +
                            std::to_string(r.xyz.size() / 3));
  const Element& conn = need_cells_array(f, piece, "connectivity");
  const Element& off = need_cells_array(f, piece, "offsets");
  const Element& types = need_cells_array(f, piece, "types");
  r.conn = f.integers(conn), r.offsets = f.integers(off), r.types = f.integers(types);
  r.conn_pos = conn.begin, r.off_pos = off.begin, r.types_pos = types.begin;
  for (std::string_view name : kRegionNames) {
    const Element* a = f.find_array("CellData", name);
    if (!a) continue;
    r.region = f.integers(*a);
    if (f.components(*a) != 1 || static_cast<std::int64_t>(r.region.size()) != r.ncells)
      f.fail(a->begin, "region array '" + std::string(name) + "' has " + std::to_string(r.region.size()) +
                           " values for " + std::to_string(r.ncells) + " cells");
    r.has_region = true;
    break;
  }
  // VTK 9 may write offsets with a leading 0 (ncells + 1 entries).
  std::vector<std::int64_t>& o = r.offsets;
  if (static_cast<std::int64_t>(o.size()) == r.ncells + 1 && !o.empty() && o[0] == 0) o.erase(o.begin());
  if (static_cast<std::int64_t>(o.size()) != r.ncells || static_cast<std::int64_t>(r.types.size()) != r.ncells)
    f.fail(r.off_pos, "NumberOfCells is " + std::to_string(r.ncells) + " but offsets has " + std::to_string(o.size()) +
                          " and types " + std::to_string(r.types.size()) + " entries");
  return r;
}

// Tets and triangles into the soup; vertex and line cells (meshio writes
// Gmsh's point and curve elements) are checked and skipped.
TetSoup assemble(const VtkXml& f, const Arrays& r) {
  TetSoup soup;
  soup.source = f.source();
  soup.points.resize(static_cast<std::size_t>(r.npoints));
  for (std::int64_t i = 0; i < r.npoints; ++i) soup.points[i] = {r.xyz[3 * i], r.xyz[3 * i + 1], r.xyz[3 * i + 2]};
  std::int64_t begin = 0;
  for (std::int64_t c = 0; c < r.ncells; ++c) {
    const std::int64_t type = r.types[c], end = r.offsets[c];
    const std::string cell = "cell " + std::to_string(c);
    if (end < begin || end > static_cast<std::int64_t>(r.conn.size()))
      f.fail(r.off_pos, cell + ": offset " + std::to_string(end) + " out of range (" + std::to_string(begin) + ".." +
                            std::to_string(r.conn.size()) + ")");
    const std::int64_t expect = nodes_of(type);
    if (expect < 0)
      f.fail(r.types_pos, cell + ": unsupported VTK cell type " + std::to_string(type) +
                              " (tetra 10, pyramid 14, wedge 13, hexahedron 12, triangle 5 and quad 9 are read, "
                              "vertex 1 and line 3 skipped)");
    if (end - begin != expect)
      f.fail(r.off_pos, cell + ": expected " + std::to_string(expect) + " node indices, got " + std::to_string(end - begin));
    std::array<std::uint32_t, 8> v{};
    for (std::int64_t k = 0; k < expect; ++k) {
      const std::int64_t idx = r.conn[begin + k];
      if (idx < 0 || idx >= r.npoints)
        f.fail(r.conn_pos, cell + ": node index " + std::to_string(idx) + " out of range (0.." +
                               std::to_string(r.npoints - 1) + ")");
      v[k] = static_cast<std::uint32_t>(idx);
    }
    begin = end;
    if (type == kVertex || type == kLine) continue;
    const bool volume = type == kTetra || type == kPyramid || type == kWedge || type == kHex;
    const std::int64_t tag = r.has_region ? r.region[c] : (volume ? 1 : 0);
    if (tag < std::numeric_limits<std::int32_t>::min() || tag > std::numeric_limits<std::int32_t>::max())
      f.fail(r.piece_pos, cell + ": region " + std::to_string(tag) + " does not fit in 32 bits");
    if (type == kTetra) {
      soup.tets.push_back({v[0], v[1], v[2], v[3]});
      soup.tet_region.push_back(static_cast<std::int32_t>(tag));
    } else if (type != kTriangle) {
      add_other(soup, type, v, static_cast<std::int32_t>(tag), c);
    } else {
      const std::array<std::uint32_t, 3> tri{v[0], v[1], v[2]};
      if (const std::string bad = io::repeated_vertex(tri, "triangle"); !bad.empty()) f.fail(r.conn_pos, cell + ": " + bad);
      soup.triangles.push_back({tri, static_cast<std::int32_t>(tag)});
    }
  }
  if (soup.tets.empty() && soup.other_cells.empty())
    f.fail(r.piece_pos, "the file holds no tetrahedra (" +
                            (r.ncells ? "none of its " + std::to_string(r.ncells) + " cells is a tetra"
                                      : std::string("NumberOfCells is 0")) + ")");
  return soup;
}

}  // namespace

TetSoup read_vtu(std::string_view bytes, const std::string& source) {
  const VtkXml file(bytes, source, "UnstructuredGrid");
  return assemble(file, read_arrays(file));
}

TetSoup read_vtu_file(const std::string& path) {
  io::InputFile file(path);
  return read_vtu(io::vtkxml::load_vtk_xml(file), path);
}

}  // namespace polydual
