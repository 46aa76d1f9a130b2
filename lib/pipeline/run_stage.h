// Internal to lib/pipeline: how a stage runs (timed, recorded, interruptible)
// and the checks every dual passes through, shared by the tet pipeline
// (convert.cpp) and the mixed one (convert_mixed.cpp).
#pragma once
#include <new>
#include <string>

#include <sys/resource.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/stopwatch.h"
#include "pipeline/convert.h"

namespace polydual::pipeline_detail {

// The process's peak resident set so far, MB (Linux: ru_maxrss in KiB).
inline double peak_rss_mb() {
  rusage u{};
  return getrusage(RUSAGE_SELF, &u) == 0 ? double(u.ru_maxrss) / 1024.0 : 0.0;
}

// Runs one stage, times it and records it; returns the stage's value. A
// pending interrupt (Ctrl-C, SIGTERM) stops the pipeline between stages.
template <class F>
auto run_stage(ConvertReport& report, const ConvertHooks& hooks, const char* name, F&& stage) {
  throw_if_interrupted();
  const Stopwatch clock;
  Json stats;
  auto value = [&] {
    try {
      return stage(stats);
    } catch (const std::bad_alloc&) {
      throw OutOfMemory(name, peak_rss_mb());
    }
  }();
  report.stages.push_back(StageRecord{name, clock.seconds(), std::move(stats), peak_rss_mb()});
  if (hooks.stage_done) hooks.stage_done(report.stages.back());
  return value;
}

// The dual's points are computed in floating point (means, normals); a mesh
// whose scale the input check let through but whose arithmetic still over- or
// underflowed is refused here, before the optimiser sees a NaN.
inline void require_finite_points(const PolyMesh& pm, const std::string& source) {
  for (std::size_t p = 0; p < pm.num_points(); ++p)
    if (!is_finite(pm.points[p]))
      throw InputError(source, "dual point " + std::to_string(p + 1),
                       "not finite: the mesh's coordinates are out of the range double arithmetic handles "
                       "(rescale the mesh)");
}

}  // namespace polydual::pipeline_detail
