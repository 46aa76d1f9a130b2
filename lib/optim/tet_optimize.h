// Condition-number optimisation of the input tets before the dual (paper
// section 4: "condition number optimization" of the tetrahedral mesh; design §7).
//
// Objective: the sum over all tet corners of kappa_mod (quality/corner.h), the
// same corner condition number the dual's optimisers use. A tet has 4 corners,
// one per vertex, with edge vectors to the other three in right-handed order,
// so kappa of a corner is the condition number of the corner's Jacobian.
// Quality of a tet: the mean of kappa/3 over its corners (regular tet 1.2247).
//
// Scheme: Gauss-Seidel Newton over vertices, one colour of a greedy vertex
// colouring at a time (no two vertices of a colour share a tet, so a colour is
// processed in parallel and the result does not depend on the thread count).
// Constraints:
//  - model vertices (dim 0) never move;
//  - vertices on a model edge (dim 1) move along the two original segments of
//    that edge at the vertex, on a model face (dim 2) over the original
//    triangles of that face around the vertex (closest point, original
//    coordinates), so they stay exactly on the original facetisation of a
//    planar entity and on it up to rounding otherwise;
//  - with move_curved off, a boundary vertex moves only where the model is
//    flat around it: every model face through it has its triangles there in
//    one plane and, on a model edge, the edge's two segments are on one line
//    (EXACT: orient3d / orient2d). The model's facetisation is then the same
//    point set (up to the rounding of the moved coordinates), so each
//    material keeps its volume (the keep mode's promise, design §4.10);
//  - a move is accepted only if every tet around the vertex stays positive by
//    the exact orient3d and the local objective decreases (step halving).
// The moves never change topology or classification. optimize_tets() then
// runs the Delaunay flip pass (optim/tet_flip.h, `flips`): moves without flips
// break the Delaunay property of the input and invert dual edges.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/json.h"
#include "mesh/classified_tet_mesh.h"
#include "optim/steiner.h"
#include "optim/tet_flip.h"

namespace polydual {

struct TetOptParams {
  // Run the stage (default on; `convert --no-optimize-tets` skips it). On the
  // corpus of tests/corpus it lowers the dual's worst cell and the cells the
  // split adds where the input has slivers (TetGen without its quality bound:
  // tetgen_star_n max kappa/3 12.7 -> 7.2, split cells +19.8 % -> +1.9 %) at
  // about 13 % of the default command's time on a 200k-tet mesh
  // (bench/README.md).
  bool enabled = true;
  // Boundary vertices also move on curved model faces and edges, over their
  // original facets (the facetisation changes: the vertices stay on the old
  // one, the new triangles are chords of it). Off: only where the model is
  // flat around the vertex (see above). PipelineParams::set_boundary turns
  // it off in the keep mode. Default on.
  bool move_curved = true;
  // Gauss-Seidel sweeps over all movable vertices, at most. Default 10.
  int max_sweeps = 10;
  // Stop when |f_prev - f| < tol * f_prev after a sweep. Default 1e-3.
  double tol = 1e-3;
  // Step halvings tried before a vertex's move is rejected. Default 20.
  int max_halvings = 20;
  // c of eq. 3 (delta of kappa_mod). Default 50 like the dual's optimiser.
  double c = 50.0;
  // The flip pass after the moves (optimize_tets only). Default on.
  TetFlipParams flips;
  // Interior points inserted before the moves where tets span the solid
  // (optimize_tets only; optim/steiner.h). Default on.
  SteinerParams steiner;

  static constexpr int kMaxSweeps = 10000, kMaxHalvings = 60;
  static constexpr double kMaxTol = 1.0, kMinDeltaC = 1.0, kMaxDeltaC = 1000.0;

  // Throws UsageError naming the first field outside its range.
  void validate() const;
  Json to_json() const;
};

// Quality of the tet (p0,p1,p2,p3): mean kappa/3 over its 4 corners; +infinity
// if a corner's volume is not positive in doubles.
double tet_quality(const Point3& p0, const Point3& p1, const Point3& p2, const Point3& p3);

struct TetQualityStats {
  std::size_t tets = 0;
  double min = 0, mean = 0, max = 0;  // of tet_quality (>= 1; larger is worse)
  Json to_json() const;
};
TetQualityStats tet_quality_stats(const ClassifiedTetMesh& mesh, std::span<const Point3> points);

struct TetOptReport {
  // before: the input; after_moves: after the sweeps; after: the result
  // (after the flips when they ran, else after_moves).
  TetQualityStats before, after_moves, after;
  int sweeps = 0;
  std::uint32_t colours = 0;
  std::size_t movable = 0;               // vertices with a degree of freedom
  std::uint64_t visits = 0, moves = 0;   // vertex visits, accepted moves (all sweeps)
  std::uint64_t rejected_invalid = 0;    // trial points rejected because a tet turned non-positive
  std::vector<double> objective;         // after sweep i (index 0: initial); rounds > 1 append theirs
  int rounds = 0;                        // moves (+ flips) rounds run
  double seconds = 0;  // the whole stage, flips and mesh rebuilds included
  bool flipped = false; // the flip pass ran (flips below)
  TetFlipReport flips;
  SteinerReport steiner;  // the interior points (when params.steiner.enabled)
  Json to_json() const;
};

// The optimised coordinates of every vertex of `mesh` (mesh unchanged).
std::vector<Point3> optimized_tet_points(const ClassifiedTetMesh& mesh, const TetOptParams& params,
                                         TetOptReport* report = nullptr);

// `mesh` with its coordinates replaced by `points` (same tets, ids and
// classification: ClassifiedTetMesh::with_points). Throws InputError naming
// the source and the tet if a tet of the result is not positive by the exact
// orient3d.
ClassifiedTetMesh with_points(const ClassifiedTetMesh& mesh, std::vector<Point3> points);

// Interior points (params.steiner.enabled), then the moves, then
// (params.flips.enabled) the flip pass: returns the mesh that results (`mesh`
// unchanged) and reports into `report` (may be null). With flips or inserted
// points the tets are renumbered (tet_flip.h); inserted vertices come after
// mesh's (steiner.h).
ClassifiedTetMesh optimize_tets(const ClassifiedTetMesh& mesh, const TetOptParams& params,
                                TetOptReport* report = nullptr);

}  // namespace polydual
