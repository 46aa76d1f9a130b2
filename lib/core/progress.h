// Progress of a long stage, reported through a callback so that lib/ never
// prints: the command shows it on stderr (a live line on a terminal), other
// programs log it or ignore it.
#pragma once
#include <functional>
#include <string>

namespace polydual {

struct ProgressEvent {
  const char* stage = "";  // "optimize", ...
  int step = 0;            // steps done (sweeps, rounds)
  int max_steps = 0;       // upper bound on the steps (the stage may stop earlier); 0 unknown
  double seconds = 0;      // since the stage started
  std::string detail;      // what the step reached ("invalid 3, mean quality 1.71")
};

using ProgressFn = std::function<void(const ProgressEvent&)>;

}  // namespace polydual
