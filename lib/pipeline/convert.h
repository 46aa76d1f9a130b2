// The library entry of polydual: the paper's pipeline as explicit stages
// (docs/design.md, "Pipeline"):
//   classify (§2.1, design §3) -> free-edge cuts (split/cuts.h) -> build dual
//   (Algorithm 1 steps 1-7) -> cleanup (§2.8) -> cells (step 8) -> check
//   (exact star test, §3.1) -> optimise (§3.3) -> check -> split rounds for
//   the cells still invalid (split/split.h) -> check. --no-split: no cuts,
//   no split stages.
// Each stage takes its own params struct and leaves a StageRecord (name,
// seconds, stats) in the report. Nothing here prints or exits; the command,
// the experiments, the benchmarks and other programs call these entries.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/json.h"
#include "core/progress.h"
#include "io/write_poly_mesh.h"
#include "io/model_names.h"
#include "mesh/classified_tet_mesh.h"
#include "mesh/primal_mesh.h"
#include "mesh/poly_mesh.h"
#include "mesh/tet_soup.h"
#include "pipeline/check.h"
#include "pipeline/params.h"
#include "quality/flatness.h"

namespace polydual {

struct StageRecord {
  std::string name;  // "classify", "dual", "check", "optimize", ...
  double seconds = 0;
  Json stats;        // the stage's own stats record
  double peak_rss_mb = 0;  // the process's peak resident memory when the stage ended (getrusage)
};

struct ConvertReport {
  std::vector<StageRecord> stages;  // in the order they ran
  std::size_t invalid_before = 0;   // invalid cells of the dual before optimisation
  std::size_t invalid_after = 0;    // ... at the end
  double seconds = 0;               // all stages
  const StageRecord* stage(const std::string& name) const;
};

// The classified input of a mixed mesh (design §14): its PrimalMesh, the
// number of cells of each type, and the names of the soup's physical groups
// by region and model face tag (what the writers name).
struct MixedPrimal {
  PrimalMesh mesh;
  std::array<std::size_t, kNumCellTypes> cell_counts{};
  ModelNames names;
  PrimalReference reference;  // what its duals are validated against (quality/primal_reference.h)
};

struct ConvertResult {
  // The classified input of a tet mesh (the optimiser and writers read it);
  // empty when the input was mixed (then `mixed` holds it).
  ClassifiedTetMesh primal;
  // The input's tets: primal's count unless the tet optimisation's flips
  // changed it (0: not set, primal's count).
  std::size_t input_tets = 0;
  std::optional<MixedPrimal> mixed;
  PolyMesh mesh;             // the polyhedral dual, optimised when asked
  CheckResult check;         // validation and exact verdicts of `mesh` as returned
  ConvertReport report;
  Json written;              // convert_file: the writer's record
  IgnoredEntities ignored;   // what the reader dropped (unattached entities)
  std::vector<std::string> warnings;  // the reader's warnings, one line each
  // convert_file: the summary's face flatness of `mesh`, measured on the other
  // core while the (serial) writer runs; empty otherwise (mesh_summary measures it).
  std::optional<FlatnessStats> flatness;
};

// What a caller sees while the pipeline runs; every member may be empty.
struct ConvertHooks {
  std::function<void(const StageRecord&)> stage_done;  // after each stage, with its record
  ProgressFn progress;                                 // within long stages (optimise)
};

// soup -> ConvertResult. A mixed soup (is_mixed_or_surface, with volume
// cells) goes build_primal -> the mixed dual (dual/primal_dual.h) -> cleanup
// -> cells -> check -> optimise -> check -> the mixed split (rounds of whole
// cuts at the vertices of the cells still invalid, pipeline/convert_mixed.h;
// --no-split: none); a surface mesh is an InputError. Throws InputError for a bad mesh (naming soup.source
// and the place) and UsageError for bad params; with params.split.require_valid
// also when a cell stays invalid or the validation of the result fails
// (r.check.validation.defects(): open cells, face errors, missing model
// entities, volume mismatches). Without it such a result is returned, its
// defects in r.check.validation for the caller to report.
ConvertResult convert(const TetSoup& soup, const PipelineParams& params, const ConvertHooks& hooks = {});

// The cells of r.mesh that the exact star test found invalid, as a Defect
// ("invalid_cells"; count 0: none): each item "cell C (vertex V, class dim D
// tag T)", V in the input numbering. The command prints it as a warning
// (at most 10 items, then "and N more"); --require-valid refuses such a mesh.
Defect invalid_cells_defect(const ConvertResult& r);

// Writes r.mesh with its verdicts as cell data ("valid", "bad_tets") and, for
// a split mesh, each cell's uncut cell ("split_from"), with the names of
// r.primal's model entities (io/write_context.h).
Json write_result(const ConvertResult& r, const std::string& path, PolyFormat format,
                  const PolyWriteOptions& options = {});

// File to file: read any tet mesh format (io/read_tet_mesh.h), convert, write
// (io/write_poly_mesh.h); the report gains the "read" and "write" stages.
// Before any work `out` is checked (io/output_guard.h: never an input, never a
// directory polydual did not write unless options.foam.force); nothing is
// written on error or interruption.
ConvertResult convert_file(const std::string& in, const std::string& out, PolyFormat format,
                           const PipelineParams& params, const ConvertHooks& hooks = {},
                           const PolyWriteOptions& options = {});

// The stages after the dual on their own (the `optimize` command starts from a
// PolyMesh read back from a file): optimise in place, then check.
struct OptimizeResult {
  OptimReport optim;
  CheckResult check;
};
OptimizeResult optimize_mesh(PolyMesh& mesh, const ClassifiedTetMesh* primal, const OptimParams& params,
                             const ProgressFn& progress = {});

}  // namespace polydual
