// `optimize`: untangle/smooth a polyhedral VTU already written by polydual.
// Without the primal tet mesh, boundary points stay fixed (their original
// facetisation is not in the VTU); --primal MESH lets them slide.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/print.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "io/output_guard.h"
#include "io/read_tet_mesh.h"
#include "io/vtu_poly_reader.h"
#include "pipeline/convert.h"
#include "pipeline/summary.h"

namespace polydual::cli {

const CommandSpec kOptimize{
    "optimize", "optimize IN.vtu -o OUT.vtu [options]",
    "Untangles and smooths a polyhedral mesh written by polydual (paper §3.3).",
    1, 1,
    {"-o", "--vtu-encoding", "--zlib", "--primal", "--require-valid", "--feature-angle", "--strong-angle", "--optimize", "--planarity", "--metric", "--derivatives", "--relaxation", "--tol", "--polish-sweeps", "--polish-share", "--worst-rounds", "--settle-move", "--max-iter", "--threads",
     "--json", "--quiet"}};

int cmd_optimize(const Settings& s) {
  if (s.out.empty()) throw UsageError("optimize needs -o OUT.vtu");
  const PolyFormat format = poly_format_for("", s.out);
  if (format != PolyFormat::Vtu) throw UsageError("optimize writes a .vtu file, not '" + s.out + "'");
  s.params.validate();
  std::vector<std::string> inputs{s.positional[0]};
  if (!s.primal.empty()) inputs.push_back(s.primal);
  check_output_target(inputs, s.out, OutputKind::File, false, ".vtu");
  Json seconds = Json::object();
  Stopwatch clock;
  PolyMesh pm = read_vtu_poly(s.positional[0]);
  seconds.set("read", clock.seconds());
  std::unique_ptr<ClassifiedTetMesh> primal;
  if (!s.primal.empty()) {
    clock = Stopwatch();
    primal = std::make_unique<ClassifiedTetMesh>(
        primal_of_dual(pm, classify(read_tet_mesh(s.primal), s.params.classify), s.params.tetopt));
    require_primal_of(pm, s.positional[0], *primal);
    seconds.set("primal", clock.seconds());
  }
  clock = Stopwatch();
  ProgressPrinter progress(s.quiet);
  const OptimizeResult r = optimize_mesh(pm, primal.get(), s.params.optim, progress.progress());
  progress.end_line();
  seconds.set("optimize", clock.seconds());
  if (s.params.split.require_valid) require_valid_mesh(r.check, s.positional[0]);
  const Json w = write_poly_mesh(pm, s.out, format, verdict_fields(r.check.verdicts), s.write);
  Json j = mesh_summary(pm, r.check, nullptr);
  j.set("input", s.positional[0]);
  j.set("output", w);
  j.set("invalid_before", r.optim.invalid_before);
  j.set("invalid_after", r.optim.invalid_after);
  j.set("optimize", r.optim.to_json());
  j.set("seconds", seconds);
  if (s.json) print_json(j);
  else std::printf("%s -> %s: invalid cells %d -> %d\n", s.positional[0].c_str(), s.out.c_str(),
                   r.optim.invalid_before, r.optim.invalid_after);
  if (const std::vector<Defect> defects = r.check.validation.defects(); !defects.empty())
    print_defects("optimize", "warning", s.out + " written, but the mesh is not sound (--require-valid refuses it):",
                  defects);
  return 0;
}

}  // namespace polydual::cli
