// The check stage's parallel paths (quality/star_verdict.cpp's verdicts from
// the mesh with per-thread stamps, mesh/validate.cpp's parallel cell checks)
// against the per-cell definitions, on a block large enough for many TBB
// tasks, with points moved so that many cells are invalid and some inverted.
#include <gtest/gtest.h>

#include <random>

#include "generate/hex_block.h"
#include "mesh/validate.h"
#include "quality/star_verdict.h"

namespace polydual {
namespace {

PolyMesh shaken_block(int n, double amount, std::uint64_t seed) {
  PolyMesh m = hex_block(n, 1.0 / n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> d(-amount / n, amount / n);
  for (std::size_t p = 0; p < m.num_points(); ++p)
    if (m.point_class[p].dim == 3) m.points[p] += Vec3{d(rng), d(rng), d(rng)};
  return m;
}

TEST(CheckParallel, VerdictsEqualThePerCellTest) {
  const PolyMesh m = shaken_block(14, 0.9, 7);
  const std::vector<CellVerdict> all = star_shaped_verdicts(m);
  ASSERT_EQ(all.size(), m.num_cells());
  std::size_t invalid = 0;
  for (std::size_t c = 0; c < m.num_cells(); ++c) {
    const CellVerdict one = star_shaped_verdict(m, CellId(c));
    ASSERT_EQ(all[c].valid, one.valid) << "cell " << c;
    ASSERT_EQ(all[c].bad_tets, one.bad_tets) << "cell " << c;
    ASSERT_EQ(all[c].total_tets, one.total_tets) << "cell " << c;
    invalid += !one.valid;
  }
  EXPECT_GT(invalid, m.num_cells() / 10);
  EXPECT_LT(invalid, m.num_cells());
}

TEST(CheckParallel, VolumesAndCountsEqualTheSerialSums) {
  PolyMesh m = shaken_block(14, 1.6, 11);
  // Points moved up to 1.6 spacings tangle some cells to a negative volume;
  // three materials, alternating by cell.
  for (std::size_t c = 0; c < m.num_cells(); ++c) m.cell_material[c] = 1 + static_cast<int>(c % 3);
  const ValidationReport r = validate(m);
  std::map<std::int32_t, double> want;
  std::size_t negative = 0;
  for (std::size_t c = 0; c < m.num_cells(); ++c) {
    const double v = cell_volume(m, CellId(c));
    want[m.cell_material[c]] += v;
    negative += v <= 0;
  }
  ASSERT_EQ(r.material_volume.size(), want.size());
  for (const auto& [tag, v] : want) EXPECT_EQ(r.material_volume.at(tag), v) << "material " << tag;  // bit for bit
  EXPECT_EQ(r.negative_volume_cells, negative);
  EXPECT_GT(negative, 0u);
  EXPECT_EQ(r.closed_cells, m.num_cells());
}

}  // namespace
}  // namespace polydual
