// Random mixed meshes for property tests (design §14, proofs/mixed_dual.md):
// the two ways real mixed meshes arise. Deterministic and portable, as
// random_mesh.h: the same parameters give the same soup everywhere.
//   - Prism layers grown on the boundary of a random classified tet mesh
//     (a CFD boundary layer: the tets' boundary triangles extruded outwards).
//   - A hexahedral block joined to tets through pyramids, its points jittered.
#pragma once
#include <cstdint>
#include <vector>

#include "generate/random_mesh.h"
#include "mesh/cell_types.h"
#include "mesh/tet_soup.h"

namespace polydual {

// The random tet mesh of `tets` (random_classified_mesh; the unit box, so
// neither `notch` nor `touching`, which make its boundary leave the box)
// with `layers` prism layers grown outwards on its whole boundary: a boundary
// point moves along the sum of the outward normals of the box faces it lies
// on, so each layer's outer surface is again a box, [-H, 1+H]^3 after a total
// height H. Layer k is first·ratio^k thick. A prism takes the region of the
// tet under its column; fracture sheets that reach the boundary end there
// (their free edges run along the tets' boundary, inside the layers). The
// outer box's faces are tagged 1..6 (-x, +x, -y, +y, -z, +z); the rest of
// the classification is inferred (build_primal). Use tets.face_points for
// boundary triangles smaller than the box's faces.
// Throws UsageError on layers < 1, first <= 0, ratio <= 0, or `tets` with
// notch or touching.
TetSoup random_prism_layers(const RandomMeshParams& tets, int layers, double first, double ratio);

// The unit box cut into n^3 cubes: hexahedra below z = 1/2 (region 1), and
// above each cube cut from its centre into faces' pyramids and tets (region
// 2): a pyramid on the bottom quadrangle of every cube of the layer just
// above the hexahedra, two tets on every other face (split along the
// diagonal from its smaller vertex, so neighbours agree). Every grid point
// moves by up to jitter·(1/n)/2 per coordinate (seeded), except across the
// box's faces (a point on a face stays on it) and across the plane z = 1/2
// (the interface stays planar); a cube's centre is its corners' mean. The
// box faces are tagged 1..6 (-x, +x, -y, +y, -z, +z). n even, n >= 2,
// 0 <= jitter < 1/2, else UsageError.
TetSoup random_hex_pyramid_tets(std::uint64_t seed, int n, double jitter);

// Building blocks of mixed soups. add_cell appends a cell of type t with its
// vertices in the local order of mesh/cell_types.h, mirrored (descriptor's
// mirror permutation) when its first corner tet is negative (exact orient3d).
void add_cell(TetSoup& s, CellType t, std::vector<std::uint32_t> v, std::int32_t region);
// Tags every boundary face whose points all lie on a face of the box
// [lo, hi]^3 with that face's side (1..6: -x, +x, -y, +y, -z, +z), as a
// triangle or a quadrangle of the soup.
void tag_box_boundary(TetSoup& s, double lo, double hi);

}  // namespace polydual
