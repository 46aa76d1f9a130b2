// The whole pipeline under the sanitizers: a small mesh of any text or binary
// format (the first byte picks the reader: 'm' Medit, 'g' Gmsh, 'v' VTU; the
// rest is the file), then classify -> dual -> cleanup -> cells -> exact star
// test and validation -> a few local optimiser sweeps -> check, through the
// library entry (lib/pipeline). Bad input must end in InputError/UsageError;
// anything else (another exception, a sanitizer finding, a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "io/medit_io.h"
#include "io/msh_reader.h"
#include "io/vtu_reader.h"
#include "pipeline/convert.h"

namespace {
// Small enough for libFuzzer's pace; a fuzzed header can claim any size.
constexpr std::size_t kMaxTets = 2000;

polydual::TetSoup read_any(char format, std::string_view body) {
  if (format == 'g') return polydual::read_msh(body, "fuzz.msh");
  if (format == 'v') return polydual::read_vtu(body, "fuzz.vtu");
  return polydual::read_medit(body, "fuzz.mesh");
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::string_view body(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const polydual::TetSoup soup = read_any(static_cast<char>(data[0]), body);
    if (soup.tets.size() > kMaxTets) return 0;
    polydual::PipelineParams params;
    params.optim.max_iter = 2;
    params.optim.untangle_sweeps = 1;
    const polydual::ConvertResult r = polydual::convert(soup, params);
    // The stages' own promises, beyond not crashing.
    if (r.check.verdicts.size() != r.mesh.num_cells()) __builtin_trap();
    if (r.report.invalid_after > r.report.invalid_before) __builtin_trap();  // the optimiser never makes a cell invalid
    if (r.check.validation.face_errors != 0) __builtin_trap();
    // Every cell closed, also where the mesh touches itself along an edge
    // (proofs/edge_chains.md; seeds two_tets_edge, cgal_junction_edge).
    if (r.check.validation.closed_cells != r.check.validation.cells) __builtin_trap();
  } catch (const polydual::InputError&) {
  } catch (const polydual::UsageError&) {
  }
  return 0;
}
