// The random classified meshes the split tests run on (split_recheck_test,
// split_local_round_test): by seed, 40 to 160 points, mostly with a fracture,
// some with a crossing sheet or two regions, some with three materials
// touching along edges (edges of several chains).
#pragma once
#include <cstdint>

#include "generate/random_mesh.h"

namespace polydual {

inline RandomMeshParams split_test_mesh_params(std::uint64_t seed) {
  RandomMeshParams p;
  p.seed = seed;
  p.num_points = 40 + int(seed % 5) * 30;
  p.fracture = seed % 4 != 0;
  p.crossing_sheet = seed % 4 == 2;
  p.regions = seed % 3 == 0 ? 2 : 1;
  p.touching = seed % 6 == 5;
  return p;
}

}  // namespace polydual
