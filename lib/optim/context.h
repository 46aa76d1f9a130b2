// Shared state of one optimize() run (internal to lib/optim).
#pragma once
#include <chrono>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "core/progress.h"
#include "optim/boundary.h"
#include "optim/optimize.h"
#include "quality/stencil.h"

namespace polydual::optim_detail {

// How a sweep of the local scheme visits its points: set by the sweep loop
// (optim/local_newton.cpp) for each sweep and handed to every visit, apart
// from the run's parameters (Context::params, fixed for the run).
struct SweepMode {
  double omega = 1.0;  // the Newton step's over-relaxation in this sweep
  // Corrected, smoothing and polish: the points of cells above this quality
  // (at the last record) use the full analytic model.
  double full_model_above = 0;
  // Corrected, untangling sweeps (None: a smoothing or polish sweep). The
  // first uses the plain lagged model (it spares the neighbours of the
  // tangled cells); the later ones, over the few cells left, the full model
  // at a point with a cell still invalid at its visit, the lagged one elsewhere.
  enum class Untangling { None, Lagged, FullWhereInvalid };
  Untangling untangling = Untangling::None;
};

// What the run fixes when it is set up: the parameters and what follows from
// them, from the mesh's topology and from its starting points. Every kernel
// reads it; nothing changes it after set-up (Context holds it const).
struct RunSetup {
  const OptimParams& params;
  MeshStencil stencil;
  std::vector<double> V0;          // eq. 3 scale per cell
  std::vector<std::uint8_t> dof;   // per point: 0 fixed, 1 edge, 2 face, 3 free
  std::span<const char> seed_cells;  // optimize()'s; empty: every point starts active
  // The OpenFOAM gate's (params.foam_gate in the local schemes, else empty):
  // per stencil loop its mesh face.
  std::vector<std::uint32_t> loop_face;
};

// One optimize() run: the mesh it moves, its fixed set-up, and the state
// the moves keep current (per-cell verdicts, qualities, energies, the gates'
// state), with the report it writes.
struct Context {
  PolyMesh& mesh;
  std::chrono::steady_clock::time_point start;
  std::chrono::steady_clock::time_point lap_start;  // of the phase being timed
  OptimReport* report = nullptr;
  std::vector<std::pair<std::string, double>> setup_phases;  // until the report is attached
  // null: boundary points fixed. Not part of the set-up: each point's current
  // primitive (its parametric place on the model) moves with the point.
  std::unique_ptr<BoundaryConstraints> bc;
  std::vector<double> cell_quality;  // per cell, of the last record() (kept current by the gates)
  const RunSetup setup;

  // The run's state.
  std::vector<std::uint8_t> cell_valid;      // exact star test, kept current
  QualityStats last_stats;                   // of the last record()
  // record() is incremental: per cell the energy of the last record; a cell
  // none of whose points was touched since (every point a scheme may have
  // written: the local scheme's visited points, every point after a global
  // round) has the same energy, quality and centre gradients (they are
  // functions of its own points, V0[c] and the run's fixed parameters).
  std::vector<double> recorded_energy;
  std::vector<char> touched;  // per point, since the last record
  bool all_touched = true;    // every point (the first record, a global round)
  const ProgressFn* progress = nullptr;      // called after each record(); may be null
  // Derivatives::Corrected: per cell the sum of d kappa_mod / d R over its
  // corners, per stencil loop the sum of d kappa_mod / d F over the loop's
  // corners (cell_energy_gradient), at the positions of the last refresh.
  std::vector<Vec3> grad_R, grad_F;

  // seeds: optimize()'s seed cells; known: the cells' exact star verdicts
  // (empty, or not one per cell: tested here).
  Context(PolyMesh& m, const ModelFacets* facets, const OptimParams& p, std::span<const char> seeds = {},
          std::span<const CellVerdict> known = {});
  double seconds() const;
  // Adds the seconds since the last lap (or the start) to phase `name` of the
  // report (report->phases, or the setup's until the report is attached).
  void lap(const char* name);
  // Total objective (parallel per cell, serial sum: deterministic).
  double objective(std::span<const Point3> pts) const;
  // Appends an IterationRecord for the mesh's current state; re-evaluates only
  // the cells with a point moved since the last record.
  void record(int iteration);
  // Whether the records carry the objective (cells' energies): not while only
  // untangling (Method::Untangle), whose stopping rule counts invalid cells;
  // its records hold the qualities only, and the first comes from the pass
  // that computes V0.
  bool records_energy() const { return setup.params.method != OptimParams::Method::Untangle; }
  // Whether the run uses the centre gradients (Corrected derivatives in a
  // scheme that smooths; untangling never uses the corrected model).
  bool uses_centre_gradients() const;
  // Energy, quality and (uses_centre_gradients) the centre gradients of the
  // given cells at the current positions: record()'s changed cells, and the
  // cells whose points a polish sweep moved.
  void refresh_cells(std::span<const std::uint32_t> cells);
  // Tangent basis of p (dof(p) orthonormal vectors).
  void basis(PointId p, Vec3 B[3]) const;

  // The acceptance gates beside the exact star test (optim/gates.cpp), each
  // a function of a cell's own points, so that the parallel sweeps may use
  // them (the cells of one point are one thread's).
  //  - OpenFOAM's checks (params.foam_gate, optim/foam_gate.h): a cell that
  //    passes must keep passing (while foam_active); foam_ok: per cell;
  //    face_base: per mesh face its fan's base point (chosen again by the
  //    repair as the points move).
  //  - The worst cell never gets worse: a valid cell may not rise above
  //    max(its quality before the move, quality_cap), quality_cap being the
  //    highest quality among the valid cells at the last record.
  //    cell_quality is kept current by every accepted move.
  std::vector<std::uint8_t> foam_ok;
  std::vector<PointId> face_base;
  double quality_cap = std::numeric_limits<double>::infinity();
  // Whether gates_accept applies the OpenFOAM gate now: in the repair, and
  // with params.foam_gate_sweeps in every move.
  bool foam_active = true;
  // The OpenFOAM gate's verdicts for the mesh as it is (no-op without foam_gate).
  void init_gates();
  // After p's move (its cells `cells`, already passing the star test for the
  // cells that were valid): whether both gates accept it. Fills q with the
  // cells' qualities at the new position.
  bool gates_accept(std::span<const std::uint32_t> cells, std::vector<double>& q) const;
  // After an accepted move: the cells' qualities (q, from gates_accept) and
  // the OpenFOAM verdicts of the cells that failed it.
  void gates_commit(std::span<const std::uint32_t> cells, std::span<const double> q);
  // The OpenFOAM verdicts of the given cells, afresh (after points were restored).
  void refresh_foam(std::span<const std::uint32_t> cells);
  // Number of cells failing the OpenFOAM gate.
  std::size_t foam_failing() const;

 private:
  // The set-up (the constructor's): stencil, dof, V0 (with the qualities
  // into cell_quality when only untangling), the OpenFOAM gate's loop faces.
  RunSetup set_up(const OptimParams& p, std::span<const char> seeds);
};

void run_local(Context& ctx);
// Min-max descent on the worst cells (worst_descent.cpp), after the local
// scheme's polish; returns the visits and accepted steps.
IterationRecord descend_worst(Context& ctx);
void run_global(Context& ctx);
// The cells above OptimReport::kWorstBound into rep.worst_cells (gates.cpp).
void list_worst_cells(const Context& ctx, OptimReport& rep);
// Moves the points of cells failing the OpenFOAM gate to make them pass
// (gates.cpp); returns the visits and accepted steps.
IterationRecord repair_foam(Context& ctx);

}  // namespace polydual::optim_detail
