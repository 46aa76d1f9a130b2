// A mixed cell soup: what build_primal() (classify/classify_primal.h) turns
// into a PrimalMesh. Cells of any type of mesh/cell_types.h in compressed rows
// (64-bit offsets: 10^9 tets hold 4*10^9 vertex slots), with the region tag
// of each and whatever classification the source carried.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "mesh/cell_types.h"
#include "mesh/tet_soup.h"

namespace polydual {

// A triangle (n == 3) or quadrangle (n == 4) the source tagged with a model
// face (3D meshes) or that is a surface cell's (2D meshes).
struct TaggedPolygon {
  std::array<std::uint32_t, 4> v{};
  std::uint8_t n = 3;
  std::int32_t tag = 0;
};

struct CellSoup {
  std::string source;  // file name, for error messages
  std::vector<Point3> points;
  std::vector<CellType> cell_type;
  std::vector<std::uint64_t> cell_offset{0};  // cell c holds cell_vertex[offset[c], offset[c+1])
  std::vector<std::uint32_t> cell_vertex;     // 0-based point indices, local order of cell_types.h
  std::vector<std::int32_t> cell_region;      // model region (3D) or surface (2D) tag per cell
  std::vector<std::uint64_t> cell_element;    // the file's element number per cell, 0 when unknown
  // Classification carried by the source: faces on model faces (3D meshes),
  // edges on model edges, vertices on model vertices.
  std::vector<TaggedPolygon> faces;
  std::vector<TaggedEdge> edges;
  std::vector<TaggedVertex> corners;

  std::size_t num_cells() const { return cell_type.size(); }
  std::span<const std::uint32_t> cell(std::size_t c) const {
    return {cell_vertex.data() + cell_offset[c], cell_vertex.data() + cell_offset[c + 1]};
  }
  void add_cell(CellType t, std::span<const std::uint32_t> v, std::int32_t region, std::uint64_t element = 0) {
    cell_type.push_back(t);
    cell_vertex.insert(cell_vertex.end(), v.begin(), v.end());
    cell_offset.push_back(cell_vertex.size());
    cell_region.push_back(region);
    cell_element.push_back(element);
  }
};

// The cell soup of a tet soup with its other cells (TetSoup::other_cells):
// the volume cells in the order tets, then the others; the tagged triangles
// and quads classify faces. A soup with no volume cell is a surface mesh:
// its triangles and quads become the cells (their tag the surface), the
// tagged edges and corners classify edges and vertices.
CellSoup cell_soup(const TetSoup& soup);

// "tetrahedron 3", "prism 12 (element 1207)": the k-th cell of its type in
// the soup's order (1-based, as the tet readers name tets), with the file's
// element number when known.
std::string cell_place(const CellSoup& soup, std::size_t c);

}  // namespace polydual
