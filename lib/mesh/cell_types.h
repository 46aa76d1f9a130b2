// The cell types of a primal mesh and their reference descriptors: local
// vertices, edges and faces, and the corner tets that decide a cell's
// orientation (design §14).
//
// Local numbering is Gmsh's (and VTK's, but for the wedge: VTK's wedge is the
// mirror image of Gmsh's prism, see kMirror). A cell is positively oriented
// when every corner tet below has positive orientation (det[b-a, c-a, d-a] >
// 0, decided exactly by the caller through lib/predicates); the reference
// elements are. Every face loop is then ordered so that its right-hand normal
// points out of the cell; for a 2D cell the loop is the cell itself and its
// "faces" are not used.
#pragma once
#include <array>
#include <cstdint>
#include <string_view>

namespace polydual {

enum class CellType : std::uint8_t { Tet = 0, Pyramid = 1, Prism = 2, Hex = 3, Triangle = 4, Quad = 5 };
inline constexpr int kNumCellTypes = 6;

struct CellDescriptor {
  CellType type;
  std::string_view name;    // "tetrahedron", ... (user messages)
  std::string_view plural;  // "tetrahedra", ...
  int dim;                  // 3 for volume cells, 2 for surface cells
  int num_vertices, num_edges, num_faces;
  std::array<std::array<std::int8_t, 2>, 12> edges;  // local vertex pairs
  // Outward face loops (3D cells), -1 padded; face_size[i] is 3 or 4.
  std::array<std::array<std::int8_t, 4>, 6> faces;
  std::array<std::int8_t, 6> face_size;
  // Corner tets (a, b, c, d): all positive iff the cell is positively oriented.
  int num_corners;
  std::array<std::array<std::int8_t, 4>, 8> corners;
  // The local permutation that turns a negatively oriented cell into a
  // positive one with the same faces (mirror image).
  std::array<std::int8_t, 8> mirror;
};

namespace detail {
inline constexpr std::int8_t X = -1;
inline constexpr std::array<CellDescriptor, kNumCellTypes> kDescriptors{{
    {CellType::Tet, "tetrahedron", "tetrahedra", 3, 4, 6, 4,
     {{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}},
     // Face i is opposite local vertex i (as kTetFace of classified_tet_mesh.h).
     {{{1, 2, 3, X}, {0, 3, 2, X}, {0, 1, 3, X}, {0, 2, 1, X}}},
     {3, 3, 3, 3, 0, 0},
     1, {{{0, 1, 2, 3}}},
     {0, 2, 1, 3, X, X, X, X}},
    {CellType::Pyramid, "pyramid", "pyramids", 3, 5, 8, 5,
     {{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}}},
     {{{0, 3, 2, 1}, {0, 1, 4, X}, {1, 2, 4, X}, {2, 3, 4, X}, {3, 0, 4, X}}},
     {4, 3, 3, 3, 3, 0},
     // The apex has four neighbours: the four base corners decide.
     4, {{{0, 1, 3, 4}, {1, 2, 0, 4}, {2, 3, 1, 4}, {3, 0, 2, 4}}},
     {0, 3, 2, 1, 4, X, X, X}},
    {CellType::Prism, "prism", "prisms", 3, 6, 9, 5,
     {{{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}}},
     {{{0, 2, 1, X}, {3, 4, 5, X}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}}},
     {3, 3, 4, 4, 4, 0},
     6, {{{0, 1, 2, 3}, {1, 2, 0, 4}, {2, 0, 1, 5}, {3, 5, 4, 0}, {4, 3, 5, 1}, {5, 4, 3, 2}}},
     {0, 2, 1, 3, 5, 4, X, X}},
    {CellType::Hex, "hexahedron", "hexahedra", 3, 8, 12, 6,
     {{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}},
     {{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}},
     {4, 4, 4, 4, 4, 4},
     8, {{{0, 1, 3, 4}, {1, 2, 0, 5}, {2, 3, 1, 6}, {3, 0, 2, 7},
          {4, 7, 5, 0}, {5, 4, 6, 1}, {6, 5, 7, 2}, {7, 6, 4, 3}}},
     {0, 3, 2, 1, 4, 7, 6, 5}},
    {CellType::Triangle, "triangle", "triangles", 2, 3, 3, 0,
     {{{0, 1}, {1, 2}, {2, 0}}}, {}, {0, 0, 0, 0, 0, 0}, 0, {}, {0, 2, 1, X, X, X, X, X}},
    {CellType::Quad, "quadrangle", "quadrangles", 2, 4, 4, 0,
     {{{0, 1}, {1, 2}, {2, 3}, {3, 0}}}, {}, {0, 0, 0, 0, 0, 0}, 0, {}, {0, 3, 2, 1, X, X, X, X}},
}};
}  // namespace detail

constexpr const CellDescriptor& descriptor(CellType t) { return detail::kDescriptors[std::size_t(t)]; }

constexpr std::string_view cell_type_name(CellType t) { return descriptor(t).name; }

}  // namespace polydual
