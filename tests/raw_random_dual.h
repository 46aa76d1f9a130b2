// The raw conversion (no split, no optimiser) of a random classified mesh:
// its primal and a dual with invalid cells, for the optimiser tests
// (optim_test, optim_speed_test).
#pragma once
#include <cstdint>

#include "generate/random_mesh.h"
#include "pipeline/convert.h"

namespace polydual {

inline ConvertResult raw_random_conversion(std::uint64_t seed, int num_points) {
  RandomMeshParams rp;
  rp.seed = seed;
  rp.num_points = num_points;
  PipelineParams pp;
  pp.split.enabled = false;
  pp.optim.method = OptimParams::Method::None;
  return convert(random_classified_mesh(rp), pp);
}

}  // namespace polydual
