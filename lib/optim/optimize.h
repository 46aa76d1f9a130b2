// Untangling and smoothing of a polyhedral mesh (paper 3.3, design §7): minimise
// the sum of kappa_mod over all corners of the chosen metric, with the paper's
// local Gauss-Seidel Newton scheme or a global Ceres L-BFGS solve, keeping boundary
// points on the original facetisation and never turning a valid cell invalid.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <span>
#include <vector>

#include "core/json.h"
#include "core/progress.h"
#include "mesh/model_facets.h"
#include "mesh/poly_mesh.h"
#include "quality/corner.h"
#include "quality/metrics.h"
#include "quality/star_verdict.h"

namespace polydual {

struct OptimParams {
  // Auto: the pipeline's default (PipelineParams): Local on tet meshes,
  // Untangle on mixed meshes, whose prism and hexahedron layers the kappa
  // objective would make isotropic (a wall cell of half the first layer's
  // height grew fourfold on a Gmsh boundary layer, experiments/boundary_layer.py).
  // optimize() runs Auto as Local.
  enum class Method : std::uint8_t { None, Local, Global, Untangle, Auto };
  enum class Derivatives : std::uint8_t { FiniteDifference, Exact, Analytic, Lagged, Corrected };

  // Optimiser. Default Local (the paper's scheme). Untangle: the local scheme's
  // untangling sweeps only (points of invalid cells and the growing rings around
  // the points that moved, same exact validity guarantee), until no cell is
  // invalid, a sweep moves nothing, or max_iter sweeps; no smoothing sweep.
  Method method = Method::Local;
  // Corner set of the objective and of the reported quality. Default Q1 (the
  // paper found it untangles faster).
  Metric metric = Metric::Q1;
  // Local scheme derivatives. Corrected (default, below). Analytic: closed-form gradient and
  // Hessian of the local objective in one pass over the point's corners
  // (proofs/quality.md §6), ~4 objective evaluations per visit against 13 for
  // FiniteDifference, the paper's reference path (central differences,
  // 1 + 2k + k(k-1) evaluations; `--derivatives fd`). Exact: gradient by
  // ceres::Jet, Hessian by central differences of it. All three minimise the
  // same objective. Lagged: analytic derivatives of the lagged local objective
  // (optim/lagged_objective.h: only the corners p enters directly, centres R
  // and F held for the visit; the line search's decrease test uses it too, the
  // exact star test the true centres). Corrected: the lagged model plus the
  // linear term of the held centres' gradient, refreshed before each pass
  // (optim/lagged_objective.h), so its fixed points are the full objective's.
  // Ignored by Global (analytic adjoint gradient).
  Derivatives derivatives = Derivatives::Corrected;
  // Local: number of Gauss-Seidel iterations (each = a surface pass then a
  // volume pass). Global: number of rounds (L-BFGS solve, projection, validity
  // check). Default 20.
  int max_iter = 20;
  // Stop when |f_prev - f| < tol * |f_prev| after an iteration (Local: after a
  // sweep of the smoothing phase). Default kMethodTol: the method's own,
  // effective_tol() -- 2e-2 for the local scheme with over-relaxation and the
  // polish (a 10^5-tet dual stops after 3 smoothing sweeps, mean quality
  // within 0.5% of the paper's scheme at 1e-3 in ~7 and a lower max: the
  // polish lowers the worst cells), 1e-3 otherwise (Global, or relaxation 1
  // without polish: ~6-8 sweeps or rounds).
  static constexpr double kMethodTol = -1.0;
  double tol = kMethodTol;
  double effective_tol() const;
  // c of eq. 3, delta = V0 / (1 + c exp(V/V0)). Default 50 (paper: 10..100).
  double c = kDefaultDeltaC;
  // Local: Newton steps per vertex visit. Default 1 (more sweeps do the rest).
  int newton_steps = 1;
  // Local: settling threshold of the active set, relative to the local length
  // cbrt(V0). A point is visited only while a cell around it is invalid or a
  // point of one of its cells moved by more than settle_move x length in this or
  // the previous sweep. Default 1e-3 (moves below it change kappa by ~1e-6
  // relative); 0 revisits every point whose neighbourhood moved at all.
  double settle_move = 1e-3;
  // Local: at most this many untangling sweeps first, visiting only the points
  // of invalid cells and the growing rings around the points that moved, while
  // invalid cells remain; then sweeps over all points. Default 5; 0 starts with
  // a sweep over all points (the paper). Every sweep counts toward max_iter.
  int untangle_sweeps = 5;
  // Local: over-relaxation factor omega of the Newton step (SOR-Newton): omega x
  // the step is tried first, then the step and its halvings (the same exact
  // validity test and Armijo decrease on each). 1 = the paper's damped Newton.
  double relaxation = 1.6;
  static constexpr double kMaxRelaxation = 1.95;
  // Local: after the smoothing stops, at most polish_sweeps sweeps over the
  // points of the cells whose quality exceeds mean + polish_share x (max - mean)
  // and of their point-sharing neighbours,
  // while the worst quality drops by more than 1e-5 (relative); they count
  // toward max_iter and are reported as one iteration. Default 8 (each at a
  // few percent of a full sweep's cost; with the min-max descent below after
  // it, a cap of 40 let cube 100k run 15 polish sweeps for a max within
  // 0.01 % of what 8 reach); 0: no polish (the paper).
  int polish_sweeps = 8;
  double polish_share = 0.9;
  // Local, at the end of the polish (when it ran): at most worst_rounds rounds
  // of min-max descent, each moving the points of the current worst cell to
  // lower the highest quality among their cells (optim/worst_descent.cpp);
  // they stop when the worst cell does not improve. The max quality never
  // rises and every cell stays valid (exact star test). In the polish's
  // record (its visits and updates). Default 100 (100k and 1M tets: 0.02-0.07 s, max -2 to -3 %); 0: none.
  int worst_rounds = 100;
  // Local and Global: step halvings tried before a move is rejected. Default 20.
  int max_halvings = 20;
  // Finite-difference step, relative to the local length cbrt(V0). Default 1e-4
  // (~eps^(1/4): balances truncation and rounding in second differences).
  double fd_step = 1e-4;
  // Local: weight W of the face-flatness term added to each point's local
  // objective (optim/planarity.h; the paper's future work). Default 0: the
  // objective of the paper, unchanged. Derivatives of the term by central
  // differences (step fd_step). Global and Untangle refuse W > 0.
  double planarity = 0;
  // Local: after the sweeps, the polish and the min-max descent, the cells
  // failing OpenFOAM's face-pyramid and face-tet checks (optim/foam_gate.h;
  // floating point, beside the exact star test) get a repair descent whose
  // moves never make a cell that passes them fail. Default true; false: no repair.
  bool foam_gate = true;
  // Local and Untangle, with foam_gate: the same gate on every move of the
  // sweeps, the polish and the min-max descent too, so that no cell that
  // passes ever fails. Default false: on TetGen sliver meshes it held the
  // worst cell at 61 against 14 and the mean at 7.0 against 4.0.
  bool foam_gate_sweeps = false;
  // Untangle, with foam_gate: the repair descent after the untangling too,
  // moving only the points of cells that fail OpenFOAM's checks. Default
  // true: without it the split's OpenFOAM rounds cut what the repair moves
  // (TetGen and CGAL meshes: up to 2.4x the cells, and faces still failing);
  // with it, 0 failing faces on the corpus at the uncut cell count. The
  // split's rounds untangle without it (their result only decides cuts).
  bool foam_repair_untangle = true;
  static constexpr double kMaxPlanarity = 1000.0;
  // Global: L-BFGS iterations per round. Default 50.
  int global_iterations_per_round = 50;
  // Boundary points keep their own primal simplex (BoundaryConstraints' own-
  // primitive constraints, optim/boundary.h): set for a dual built with
  // DualParams::boundary == Keep (PipelineParams::set_boundary keeps the two
  // in step). Default false: points slide over their model entity (paper 3.3).
  bool keep_boundary = false;

  // Ranges checked by validate() (and printed by the command's help).
  static constexpr int kMaxIterLimit = 100000;
  static constexpr double kMaxTol = 1.0;
  static constexpr double kMinDeltaC = 1.0, kMaxDeltaC = 1000.0;  // paper: 10..100
  static constexpr int kMaxNewtonSteps = 100, kMaxUntangleSweeps = 1000, kMaxHalvings = 60;
  static constexpr double kMaxFdStep = 0.1;
  static constexpr double kMaxSettleMove = 1.0;

  // Throws UsageError naming the first field outside its range.
  void validate() const;
  // Every field (method, metric and derivatives by name).
  Json to_json() const;
};

struct IterationRecord {
  int iteration = 0;           // 0 = initial state
  double objective = 0;        // sum of kappa_mod over all corners (NaN while only untangling: not evaluated)
  std::size_t invalid = 0;     // invalid cells, exact star test
  double min_quality = 0;      // over untangled cells, kappa/3
  double mean_quality = 0;
  double max_quality = 0;
  double seconds = 0;          // wall time since the start of optimize()
  std::uint64_t visited = 0;   // Local: points visited in this sweep (active set)
  std::uint64_t updates = 0;   // Local: accepted moves in this sweep
  std::uint64_t full_model = 0;  // Local: visits that used the full analytic model
  Json to_json() const;
};

// A cell left above OptimReport::kWorstBound: its points that no move may
// displace (dof 0: model vertices, unclassified points, boundary points when
// no primal constrains them) with their model entities, and how many of its
// points slide on a model edge or face.
struct WorstCell {
  std::uint32_t cell = 0;
  double quality = 0;
  std::vector<std::pair<PointId, ModelRef>> pinned;
  std::uint32_t on_edges = 0, on_faces = 0;
  Json to_json() const;
};

struct OptimReport {
  std::vector<IterationRecord> iterations;
  // Cells failing the OpenFOAM gate (OptimParams::foam_gate) before and after,
  // and the failing cells after the run (increasing): the cells a split
  // would have to cut for OpenFOAM to find no wrongly oriented face pyramid
  // or face tet.
  std::size_t foam_failing_before = 0, foam_failing_after = 0;
  std::vector<std::uint32_t> foam_failing_cells;
  // The cells above kWorstBound after the run, worst first, at most kMaxWorstCells.
  static constexpr double kWorstBound = 10.0;
  static constexpr std::size_t kMaxWorstCells = 20;
  std::vector<WorstCell> worst_cells;
  std::size_t cells_above_bound = 0;
  int invalid_before = 0, invalid_after = 0;
  QualityStats before, after;
  double seconds = 0;
  std::uint64_t vertex_updates = 0;  // accepted point moves (Local) / moved points x rounds (Global)
  std::uint32_t colours = 0;         // Local: independent sets of the surface + volume passes
  // Wall seconds of the run's parts, in the order they first ran: the setup
  // (stencil, constraints, reference_volumes, verdicts), record (the
  // iterations' energies and qualities), colouring (local), iterations (the
  // sweeps' point visits, the global solver's rounds).
  std::vector<std::pair<std::string, double>> phases;
  Json to_json() const;
};

// Optimises `mesh` in place. With facets == nullptr boundary points (dim 0..2)
// are fixed; otherwise dim-1/2 points slide on the model edges' segments and
// the model faces' triangles of `facets` (model_facets() of the primal).
// `progress` (may be empty) is called after every iteration with its record.
// seed_cells (Local and Untangle; empty: every point, the default): the
// smoothing starts from the points of these cells only and spreads by the
// settling rule, but moves no point farther than 3 point-sharing cell layers
// from a seed or invalid cell (a re-optimisation after a local change, e.g.
// the split: the rest of the mesh stays as it was).
// known (empty: computed here): the exact star verdicts of mesh as it is, one
// per cell (check_mesh's, quality/check_result.h), so that the optimiser does not
// test every cell again before it starts.
OptimReport optimize(PolyMesh& mesh, const ModelFacets* facets, const OptimParams& params,
                     const ProgressFn& progress = {}, std::span<const char> seed_cells = {},
                     std::span<const CellVerdict> known = {});

// CLI parsers; throw UsageError on an unknown value.
OptimParams::Method parse_method(std::string_view s);             // auto|none|untangle|local|global
Metric parse_metric(std::string_view s);                          // q1|q2
OptimParams::Derivatives parse_derivatives(std::string_view s);   // analytic|corrected|lagged|fd|exact
const char* method_name(OptimParams::Method m);
const char* derivatives_name(OptimParams::Derivatives d);

}  // namespace polydual
