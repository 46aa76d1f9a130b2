// Interior points for tet meshes whose tets span the solid (the tet stage,
// design §7; proofs/tet_optimize.md T6).
//
// Why: a mesh with (almost) no interior vertex, such as TetGen's `-pY`
// without its quality bound or a volume bound on a thick solid, has tets that
// reach from one side of the solid to the other. Every dual cell is then a
// slab from its boundary vertex deep into the solid, and the optimiser leaves
// many tangled: on six such TetGen meshes of thick CAD solids (a torus, a
// cone on a box, a ball in a box, crossing cylinders) the split ended at
// +130-977 % cells, max kappa/3 13-47, in 23-56 s for 3-12k tets, where TetGen
// with interior points (`-a`) gives +0 %, kappa/3 3, 0.6 s (bench/README.md).
//
// What: while a tet is large against the mesh size around it (every vertex
// of it farther from its centroid than `ratio` times the mean size h of its
// vertices; h of a vertex: the mean length of its edges on model faces and
// edges, or of all its edges for an interior vertex; an inserted vertex takes
// its tet's), the centroid is inserted by Bowyer-Watson: the cavity of the
// tets whose circumsphere holds it strictly (EXACT insphere), grown from its
// tet through faces on no model face, shrunk until the point sees every
// cavity face (EXACT orient3d: every new tet positive), is replaced by the
// point joined to the cavity's faces. An insertion that would remove a
// vertex, a constrained edge (on a model edge or face) or a model-face
// triangle, or make a tet worse than max(1e3, the worst it replaces), is
// skipped. Model faces, edges and vertices are untouched: every model-face
// triangle, every region's tets' union and the boundary stay exactly as they
// were; the regions' volumes too. Tets of a regular mesh (centroid at 0.61
// of its edge from each vertex) are never split.
//
// Deterministic: serial, in slot order; the result does not depend on the
// thread count.
#pragma once
#include <cstddef>
#include <string>

#include "core/json.h"
#include "mesh/classified_tet_mesh.h"

namespace polydual {

struct SteinerParams {
  // Insert interior points (`--interior-points on|off`). Default on.
  bool enabled = true;
  // A tet is split when each vertex is farther than ratio * h from its
  // centroid (a regular tet: 0.61). Default 2: on the six TetGen meshes
  // above it inserts 53-305 points (1-3 % of the tets) and every one ends
  // with no split cell, max kappa/3 2.5-3.5, in 1.0-2.5 s; ratio 1 inserts
  // ~10x as many points for the same validity. Either leaves Gmsh's,
  // Netgen's, CGAL's and TetGen's quality meshes of tests/corpus untouched.
  double ratio = 2.0;
  // The ratio when the dual gets no optimiser (`--optimize none`, set by the
  // pipeline): its points stay at the paper's central points, which need
  // better tets. On the four TetGen -pY meshes of tests/corpus the dual
  // without optimiser then has 1.19-1.46x the default's uncut cells, against
  // 1.70-1.98x at 2 (torus: 1,484 cells against 2,479); Gmsh's, CGAL's and
  // TetGen -q's meshes still get no point, a Netgen mesh one. Default 1.3.
  double ratio_without_optimiser = 1.3;
  // Passes over the tets, at most (a pass inserts into the tets that were
  // candidates at its start). Default 8.
  int max_passes = 8;
  // Points inserted, at most, as a multiple of the mesh's vertices. Default 1.
  double max_points_per_vertex = 1.0;

  static constexpr int kMaxPasses = 100;
  static constexpr double kMinRatio = 0.7, kMaxRatio = 100.0;
  // Throws UsageError naming a field outside its range.
  void validate() const;
  Json to_json() const;
};

struct SteinerReport {
  std::size_t interior_vertices_before = 0;  // of the mesh given
  std::size_t candidates = 0;                // tets found too large (all passes)
  std::size_t inserted = 0;
  // Candidates not split, by cause: the point's tet itself failed the
  // visibility (a cavity face through it), the cavity held a vertex, a
  // constrained edge or a model-face triangle, or a new tet was too bad.
  std::size_t skipped_visibility = 0, skipped_topology = 0, skipped_quality = 0;
  int passes = 0;
  bool hit_limit = false;
  // Non-empty: the tets with the points were not a conformal mesh (the
  // rebuild's message; not seen) and the mesh was returned without them.
  std::string failed;
  double seconds = 0;
  Json to_json() const;
};

// `mesh` with interior points inserted (as above); `mesh` itself when none
// is. New vertices come after mesh's, classified on their region, with input
// numbers after the last of mesh's; the tets are renumbered as by
// delaunay_flips (optim/tet_flip.h).
ClassifiedTetMesh insert_interior_points(const ClassifiedTetMesh& mesh, const SteinerParams& params,
                                         SteinerReport* report = nullptr);

}  // namespace polydual
