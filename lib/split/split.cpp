#include "split/split.h"

#include <string>

#include "core/error.h"

namespace polydual {

void SplitParams::validate() const {
  if (max_rounds < 0 || max_rounds > kMaxRounds)
    throw UsageError("split max rounds " + std::to_string(max_rounds) + " is outside [0, " +
                     std::to_string(kMaxRounds) + "]");
}

Json SplitParams::to_json() const {
  Json j = Json::object();
  j.set("enabled", enabled);
  j.set("max_rounds", max_rounds);
  j.set("require_valid", require_valid);
  j.set("coarsen", coarsen);
  return j;
}

}  // namespace polydual
