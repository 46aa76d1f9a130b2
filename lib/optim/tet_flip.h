// Delaunay flips of a classified tet mesh (proofs/tet_optimize.md).
//
// Why: the tet optimiser (optim/tet_optimize.h) moves vertices and keeps the
// topology, so a Delaunay input loses the Delaunay property on many faces;
// across such a face the two circumcentres (the dual points) swap sides and
// the dual edge is inverted. This pass restores the property by Lawson flips
// where the classification allows it (a constrained Delaunay repair).
//
// Flips: 2-3 (an interior face whose two tets form a convex bipyramid becomes
// the three tets around the edge joining the two far vertices) and 3-2 (an
// interior edge with exactly three tets, reflex at the tested face, becomes
// the two tets of the triangle of the three far vertices). A face is flipped
// only if it fails the exact insphere test (the far vertex of the neighbour
// strictly inside the tet's circumsphere).
//
// Constraints (the classified structure is preserved exactly):
//  - a triangle on a model face (boundary, interface, fracture) is never
//    removed; an edge classified on a model edge or face (dim < 3) is never
//    removed; vertices are neither moved, added nor removed;
//  - every tet created is positive by the exact orient3d, and its quality
//    (tet_quality, floating point) at most 1e3 or the worst of the tets it
//    replaces: Lawson flips on near-cospherical points otherwise make tets
//    flat to rounding;
//  - the tets of a flip all lie in one region (implied: their shared
//    triangles are not on a model face) and the new tets get that region.
// New triangles and edges lie inside one region: unclassified triangles and
// edges classified on that region, as classify() gives them.
//
// Termination: every flip replaces the upper by the lower of the two
// triangulations of its five points lifted to the paraboloid, so the volume
// under the lifted piecewise-linear surface strictly decreases; there are
// finitely many triangulations. `max_flips_per_tet` only bounds the time.
// Serial and in a fixed order: the result does not depend on the thread count.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/json.h"
#include "mesh/classified_tet_mesh.h"

namespace polydual {

struct TetFlipParams {
  // Run the pass after the tet optimiser's moves (`--tet-flips on|off`). Default on.
  bool enabled = true;
  // At most max_flips_per_tet * (number of tets) flips; the pass stops there
  // and reports hit_limit. Default 50 (never reached in the measured runs).
  int max_flips_per_tet = 50;
  // optimize_tets(): the moves (to convergence) then the flips, `rounds`
  // times (the moves improve the tets the flips made, the last flips restore
  // the Delaunay property). Default 1.
  int rounds = 1;

  static constexpr int kMaxFlipsPerTet = 100000, kMaxRounds = 100;
  // Throws UsageError naming a field outside its range.
  void validate() const;
  Json to_json() const;
};

// Interior triangles (two tets) that are not locally Delaunay by the exact
// insphere test, split by whether the triangle is on a model face (a flip
// may not remove it) or not.
struct DelaunayCount {
  std::size_t free = 0;         // not on a model face
  std::size_t constrained = 0;  // on a model face (interface, fracture)
};
DelaunayCount count_non_delaunay(const ClassifiedTetMesh& mesh);

struct TetFlipReport {
  DelaunayCount before, after;
  std::uint64_t flips23 = 0, flips32 = 0;
  // Tests of a non-Delaunay free face that found no flip, by cause (a face
  // tested again after a neighbouring flip counts again): the two tets are
  // not convex and the reflex edge has not exactly three tets (`nonconvex`),
  // the far vertices' segment meets an edge of the face (`degenerate`, a 4-4
  // configuration), or the reflex edge is on a model edge or face
  // (`constrained_edge`).
  std::uint64_t blocked_nonconvex = 0, blocked_degenerate = 0, blocked_constrained_edge = 0;
  std::uint64_t blocked_worse_tet = 0;
  // Non-empty: the flipped tets were not a conformal mesh (the message of the
  // rebuild's error) and the input was returned unflipped.
  std::string failed;  // a new tet past the flip's quality bound (tet_flip.cpp)
  std::size_t tets_before = 0, tets_after = 0;
  bool hit_limit = false;
  double seconds = 0;
  Json to_json() const;
  // Adds another pass's counts (flips, blocked, seconds, hit_limit); `before`
  // stays this one's, `after` and `tets_after` become other's.
  void accumulate(const TetFlipReport& other);
};

// `mesh` after the flips (same vertices, classification and model; the tets
// are renumbered: untouched tets keep their order, new ones take freed slots
// or come last). A new tet's input_tet() is that of a tet its flip removed.
ClassifiedTetMesh delaunay_flips(const ClassifiedTetMesh& mesh, const TetFlipParams& params,
                                 TetFlipReport* report = nullptr);

}  // namespace polydual
