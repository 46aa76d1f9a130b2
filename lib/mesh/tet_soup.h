// What a reader or generator hands over: tets with region tags and whatever
// classification the source carried. classify() (lib/classify) validates it and
// turns it into a ClassifiedTetMesh.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "mesh/cell_types.h"

namespace polydual {

struct TaggedTriangle {
  std::array<std::uint32_t, 3> v{};
  std::int32_t tag = 0;  // model face tag
};
struct TaggedEdge {
  std::array<std::uint32_t, 2> v{};
  std::int32_t tag = 0;  // model edge tag
};
struct TaggedQuad {
  std::array<std::uint32_t, 4> v{};
  std::int32_t tag = 0;  // model face tag (a surface's tag in a surface mesh)
};
// A volume cell other than a tet (pyramid, prism, hexahedron), local order of
// mesh/cell_types.h; unused slots of v are 0.
struct SoupCell {
  CellType type = CellType::Hex;
  std::array<std::uint32_t, 8> v{};
  std::int32_t region = 0;
  std::uint64_t element = 0;  // the file's element number, 0 when unknown
};
struct TaggedVertex {
  std::uint32_t v = 0;
  std::int32_t tag = 0;  // model vertex tag
};

// Lower-dimensional input the reader dropped because it is not attached to
// the tets: points/curves/surfaces count model entities of dimension 0/1/2
// left with no element on the tet mesh (construction points, free curves, the
// parts of internal sheets outside the volume, entities the file declares but
// gives no element); elements counts the elements dropped (a vertex no tet
// uses, a repeated vertex as on a collapsed curve, or an element of a chain);
// chains counts the homology and cohomology chains Gmsh added to the mesh
// (io/unattached.h; their entities are counted as points, curves, surfaces).
struct IgnoredEntities {
  std::size_t points = 0, curves = 0, surfaces = 0, elements = 0, chains = 0;
  bool any() const { return points + curves + surfaces + elements + chains > 0; }
};

// A named (or numbered) group of the source: a Gmsh physical group. `entities`
// are the tags it holds as this soup carries them: tet_region values for
// dim 3, triangle / edge / corner tags for dim 2 / 1 / 0 (sorted, distinct).
struct NamedGroup {
  int dim = 0;
  std::int32_t tag = 0;
  std::string name;  // "" when the file gives no name
  std::vector<std::int32_t> entities;
};

struct TetSoup {
  std::string source;                             // file name, for error messages
  std::vector<Point3> points;
  std::vector<std::array<std::uint32_t, 4>> tets;  // 0-based point indices
  std::vector<std::int32_t> tet_region;           // model region tag per tet
  // Optional classification carried by the source. Triangles: boundary,
  // interface and fracture triangles with their model face tag. Edges: primal
  // edges on model edges. Vertices: primal vertices on model vertices.
  std::vector<TaggedTriangle> triangles;
  std::vector<TaggedEdge> edges;
  std::vector<TaggedVertex> corners;
  // A mixed mesh's other volume cells and its quadrangles (boundary or
  // surface elements). The tet path (classify, ClassifiedTetMesh) refuses a
  // soup that holds any (mixed_cell_counts below); mesh/cell_soup.h takes
  // them to the primal of any cell type.
  std::vector<SoupCell> other_cells;
  std::vector<TaggedQuad> quads;
  // True when the source classifies every boundary/interface entity (Gmsh msh4
  // with $Entities): classify() then checks the given classification instead of
  // inferring it, and reports contradictions.
  bool full_classification = false;
  // What the reader dropped (see IgnoredEntities) and why, one line each
  // starting with the file name, for the command to print on stderr.
  IgnoredEntities ignored;
  std::vector<std::string> warnings;
  // Physical groups, sorted by (dim, tag).
  std::vector<NamedGroup> groups;
};

// Per CellType (index = the enum's value): how many cells of each type the
// soup holds, counting tets, other cells, and (for a soup with no volume
// cell, a surface mesh) triangles and quads.
std::array<std::size_t, kNumCellTypes> mixed_cell_counts(const TetSoup& soup);
// True when the soup is not a plain tet mesh (other cells, or a surface mesh
// of triangles and quads with no tet).
bool is_mixed_or_surface(const TetSoup& soup);
// "12 tetrahedra, 30 prisms, 4 pyramids": the nonzero counts, in type order.
std::string describe_cell_counts(const std::array<std::size_t, kNumCellTypes>& counts);

}  // namespace polydual
