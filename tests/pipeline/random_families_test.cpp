// The split's workload on the random families (lib/generate/random_mesh.h): the
// default pipeline (dual, exact check, default optimiser) on each family, with
// the number of cells still invalid afterwards printed per family. The test
// holds what must stay true whatever the optimiser does: the duals are closed
// with no face errors, the optimiser never adds invalid cells, and the sheet
// families have slit cells (sheets ending inside). Small sizes keep it a unit
// test; the report's figures used kSeeds = 10, num_points = 150.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "generate/random_mesh.h"
#include "pipeline/convert.h"

namespace polydual {
namespace {

struct Family {
  const char* name;
  void (*set)(RandomMeshParams&);
};

constexpr Family kFamilies[] = {
    {"plain", [](RandomMeshParams&) {}},
    {"fracture", [](RandomMeshParams& p) { p.fracture = true; }},
    {"crossing", [](RandomMeshParams& p) { p.fracture = p.crossing_sheet = true; }},
    {"network", [](RandomMeshParams& p) { p.network = true; }},
    {"fins", [](RandomMeshParams& p) { p.fins = true; }},
    {"notch", [](RandomMeshParams& p) { p.notch = true; }},
    {"touching", [](RandomMeshParams& p) { p.touching = true; }},
};

TEST(RandomFamilies, InvalidCellsAfterDefaultOptimiser) {
  constexpr int kSeeds = 3;
  for (const Family& f : kFamilies) {
    std::size_t cells = 0, before = 0, after = 0, slit = 0, split_slit = 0, split_after = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      RandomMeshParams p;
      p.seed = static_cast<std::uint64_t>(seed);
      p.num_points = 60;
      f.set(p);
      // The split's workload: the dual without cuts (--no-split).
      PipelineParams no_split;
      no_split.split.enabled = false;
      const TetSoup soup = random_classified_mesh(p);
      const ConvertResult r = convert(soup, no_split);
      // The default (free-edge cuts): no slit cell left, every cell closed.
      const ConvertResult cut = convert(soup, PipelineParams{});
      EXPECT_EQ(cut.check.validation.slit_cells, 0u) << f.name << " seed " << seed;
      EXPECT_EQ(cut.check.validation.face_errors, 0u) << f.name << " seed " << seed;
      EXPECT_EQ(cut.check.validation.closed_cells, cut.check.validation.cells) << f.name << " seed " << seed;
      split_slit += cut.check.validation.slit_cells;
      split_after += cut.report.invalid_after;
      EXPECT_LE(r.report.invalid_after, r.report.invalid_before) << f.name << " seed " << seed;
      EXPECT_EQ(r.check.validation.face_errors, 0u) << f.name << " seed " << seed;
      EXPECT_EQ(r.check.validation.closed_cells, r.check.validation.cells) << f.name << " seed " << seed;
      cells += r.mesh.num_cells();
      before += r.report.invalid_before;
      after += r.report.invalid_after;
      slit += r.check.validation.slit_cells;
    }
    std::printf("family %-9s %2d meshes of 60 random points: %6zu cells, invalid before %4zu, after %4zu "
                "(slit cells %4zu); split by default: invalid after %4zu, slit cells %zu\n",
                f.name, kSeeds, cells, before, after, slit, split_after, split_slit);
    const std::string name = f.name;
    if (name != "plain" && name != "notch" && name != "touching")
      EXPECT_GT(slit, 0u) << f.name << ": the sheets must end inside somewhere (fracture tips)";
  }
}

}  // namespace
}  // namespace polydual
