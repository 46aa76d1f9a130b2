// Random and structured classified tet meshes for property tests and fuzzing
// (design §10: every invariant is checked on generated meshes). Deterministic and
// portable: the same parameters give the same mesh on every platform.
#pragma once
#include <cstdint>

#include "mesh/tet_soup.h"

namespace polydual {

struct RandomMeshParams {
  // Seed of the point generator (std::mt19937_64, mapped to doubles by our own
  // bit manipulation: std::uniform_real_distribution is implementation-defined).
  std::uint64_t seed = 0;
  // Random points strictly inside the unit box, added to its 8 corners.
  int num_points = 60;
  // Random points on each of the box's six faces (strictly inside the face),
  // drawn after the inner points: boundary triangles smaller than the box's
  // faces (the prism layers of generate/random_mixed.h grow on them).
  int face_points = 0;
  // 1: one region (tag 1). 2: tets with centroid x < 0.5 get tag 1, others 2 —
  // a jagged material interface.
  int regions = 1;
  // Adds a zigzag internal surface with free edges (tag kRandomFractureTag, see
  // random_classified_mesh).
  bool fracture = false;
  // Adds a second sheet (tag kRandomFractureTag + 1) between tets whose
  // centroids lie on opposite sides of y = 0.5 and both have x > 0.3: it
  // crosses the first sheet along a line, ends inside at x ~ 0.3 and reaches
  // the outer boundary at x = 1. Needs fracture.
  bool crossing_sheet = false;
  // Fracture network: the two sheets above (fracture and crossing_sheet are
  // implied) and a third one (tag kRandomFractureTag + 4) between tets whose
  // centroids lie on opposite sides of x = 0.5 with y and z in (0.2, 0.8): it
  // crosses both along lines, the three lines meet near (0.5, 0.5, 0.5), and it
  // ends inside on all four sides.
  bool network = false;
  // Two fins attached to the outer wall along a line and ending inside: tag
  // kRandomFractureTag + 2 across y = 0.5 for x < 0.35, z in (0.25, 0.75)
  // (attached to x = 0); tag kRandomFractureTag + 3 across z = 0.5 for x > 0.65,
  // y in (0.25, 0.75) (attached to x = 1).
  bool fins = false;
  // Concave model corners: tets whose centroids lie in the octant x, y, z > 0.5
  // are removed (a Fichera-like notch; unused points are dropped), so the outer
  // boundary has re-entrant edges and a re-entrant vertex. With fracture sheets
  // the sheets inside the notch go with their tets.
  bool notch = false;
  // Three materials and the outside meeting along a line, as where the
  // materials of a labelled image touch (meshed by CGAL Mesh_3): tets whose
  // centroids have z < 0.5 are region 1; above, those with x, y < 0.5 region
  // 2, with x, y > 0.5 region 3, and the tets of the other two quadrants are
  // removed (`regions` is ignored). Points on the line x = y = 0.5 (z = 0.5,
  // 0.625, ..., 1) are added. The two upper blocks then touch along edges
  // and at vertices near that line with the outside on both sides: edges
  // whose tets fall into several chains (proofs/edge_chains.md), which the
  // mesh keeps (unlike the notch).
  bool touching = false;
  // Adds what real files carry beside the tets (io/unattached.h): three points
  // above the box used by no tet, a construction point (corner, tag
  // kRandomUnattachedTag) on one of them, a free curve and a free sheet
  // triangle through them, a degenerate curve (repeated vertex), and, with
  // fracture, a part of the sheet outside the volume (a fracture-tagged
  // triangle from a box corner to two of the outside points). A reader drops
  // them all (io::drop_unattached); classify() alone refuses them.
  bool unattached = false;
  // Snap the random points to the grid of spacing 1/8 (duplicates merged): many
  // coplanar and cospherical points, the degenerate inputs exact predicates
  // must survive. Points may then also lie on the box's faces and edges.
  bool lattice_points = false;
};

inline constexpr std::int32_t kRandomFractureTag = 100;
inline constexpr std::int32_t kRandomUnattachedTag = 900;

// Delaunay tetrahedralisation (CGAL, exact predicates) of the unit box corners
// plus the random points; all tets positively oriented, region tags as above.
// With fracture: tagged triangles between two tets of one region whose centroids
// lie on opposite sides of z = 0.5 and both have x < 0.6 — a zigzag sheet that
// ends inside the mesh (fracture tips). Boundary and interface triangles are
// not listed (classify() infers them); full_classification = false.
// Throws UsageError on num_points < 0, regions not in {1, 2}, or notch and
// touching together.
TetSoup random_classified_mesh(const RandomMeshParams& params);

// Box [0, nx·hx] x [0, ny·hy] x [0, nz·hz] of nx·ny·nz cells, each split into the
// 6 Kuhn (Freudenthal) tets around the cell's diagonal from its min to its max
// corner; the same diagonal direction in every cell makes the mesh conformal.
// Every tet has volume hx·hy·hz/6 and is positively oriented. regions = 2 tags
// cells with i < nx/2 as 1 and the rest as 2 (nx must be even).
// Throws UsageError on non-positive sizes or spacings, or an odd nx with regions = 2.
TetSoup kuhn_lattice(int nx, int ny, int nz, double hx = 1, double hy = 1, double hz = 1,
                     int regions = 1);

}  // namespace polydual
