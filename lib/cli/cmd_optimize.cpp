// `optimize`: untangle/smooth a polyhedral VTU already written by polydual.
// Without the primal tet mesh, boundary points stay fixed (their original
// facetisation is not in the VTU); pass --primal MESH to let them slide.
#include <cstdio>
#include <iostream>

#include "cli/commands.h"
#include "cli/pipeline.h"
#include "core/error.h"
#include "io/vtu_poly_reader.h"
#include "optim/optimize.h"

namespace polydual::cli {

const CommandSpec kOptimize{
    "optimize", "optimize IN.vtu -o OUT.vtu [options]",
    "Untangles and smooths a polyhedral mesh written by polydual (paper §3.3).",
    1, 1,
    {{"-o", "OUT", "output .vtu (required)"},
     {"--primal", "MESH", "the tet mesh IN was built from: boundary points then slide on its model faces/edges"},
     {"--feature-angle", "DEG", "for --primal (default 30)"},
     {"--optimize", "local|global", "optimiser (default local)"},
     {"--metric", "q1|q2", "quality measure (default q1)"},
     {"--derivatives", "analytic|fd|exact", "local scheme derivatives (default analytic; fd = the paper)"},
     {"--max-iter", "N", "iterations cap (default 20)"},
     {"--json", "", "print one JSON summary object"}}};

int cmd_optimize(const Args& a) {
  if (!a.has("-o")) throw UsageError("optimize needs -o OUT.vtu");
  OptimParams p;
  if (a.has("--optimize")) p.method = parse_method(a.get("--optimize"));
  if (a.has("--metric")) p.metric = parse_metric(a.get("--metric"));
  if (a.has("--derivatives")) p.derivatives = parse_derivatives(a.get("--derivatives"));
  p.max_iter = static_cast<int>(a.get_int("--max-iter", p.max_iter));
  Json seconds = Json::object();
  Timer t;
  PolyMesh pm = read_vtu_poly(a.positional[0]);
  seconds.set("read", t.seconds());
  std::unique_ptr<ClassifiedTetMesh> primal;
  if (a.has("--primal")) {
    ClassifyParams cp;
    cp.feature_angle_deg = a.get_double("--feature-angle", cp.feature_angle_deg);
    primal = std::make_unique<ClassifiedTetMesh>(load_classified(a.get("--primal"), cp, seconds));
  }
  Timer to;
  OptimReport rep = optimize(pm, primal.get(), p);
  seconds.set("optimize", to.seconds());
  std::vector<CellVerdict> verdicts = star_shaped_verdicts(pm);
  Json w = write_poly(pm, verdicts, a.get("-o"), "vtu");
  Json j = poly_summary(pm, verdicts, nullptr);
  j.set("input", a.positional[0]);
  j.set("output", w);
  j.set("invalid_before", rep.invalid_before);
  j.set("invalid_after", rep.invalid_after);
  j.set("optimize", rep.to_json());
  j.set("seconds", seconds);
  if (a.has("--json")) std::cout << j.dump() << "\n";
  else std::printf("%s -> %s: invalid cells %d -> %d\n", a.positional[0].c_str(), a.get("-o").c_str(),
                   rep.invalid_before, rep.invalid_after);
  return 0;
}

}  // namespace polydual::cli
