// Coarsening of whole cuts (split/coarsen.h, proofs/split.md L6): the
// barycentric corners of each whole vertex are merged back while every cell
// stays valid. Checked: every result valid and sound, never more cells than
// without it and fewer over a family; without optimisation (every point of
// a whole vertex at its barycentre) each vertex's cells fill exactly the
// volume they filled before, vertex by vertex (a merged cell is the union of
// its corners, and the neighbours' cells are unchanged: the whole vertex's
// triangles keep their centres, dual/cut_topology.h kCentre); outputs are
// the same for one and two threads.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include <tbb/global_control.h>

#include "generate/random_mesh.h"
#include "mesh/validate.h"
#include "pipeline/convert.h"

namespace polydual {
namespace {

RandomMeshParams coarsen_mesh(int i) {
  RandomMeshParams mp;
  mp.seed = std::uint64_t(7000 + i);
  mp.num_points = 24 + (i % 6) * 10;
  mp.notch = i % 2 == 0;
  mp.lattice_points = i % 3 == 0;
  mp.fracture = i % 4 == 1;
  mp.regions = i % 5 == 2 ? 2 : 1;
  return mp;
}

ConvertResult run(const TetSoup& soup, OptimParams::Method method, bool coarsen) {
  PipelineParams p;
  p.optim.method = method;
  p.split.max_rounds = 1;  // the closure then cuts many vertices whole
  p.split.coarsen = coarsen;
  return convert(soup, p);
}

// Per primal vertex (input numbering), the summed volume of its cells.
std::map<std::uint32_t, double> vertex_volumes(const PolyMesh& pm) {
  std::map<std::uint32_t, double> v;
  for (std::size_t c = 0; c < pm.num_cells(); ++c) v[pm.cell_primal[c].idx] += cell_volume(pm, CellId(c));
  return v;
}

TEST(SplitCoarsen, RandomMeshesStayValidWithFewerCells) {
  std::size_t fine = 0, coarse = 0, merged_unoptimised = 0;
  for (int i = 0; i < 30; ++i) {
    const TetSoup soup = random_classified_mesh(coarsen_mesh(i));
    const auto method = i % 5 == 0 ? OptimParams::Method::Local : OptimParams::Method::None;
    const ConvertResult off = run(soup, method, false);
    const ConvertResult on = run(soup, method, true);
    ASSERT_EQ(on.check.invalid_cells, 0u) << "mesh " << i;
    EXPECT_TRUE(on.check.validation.ok()) << "mesh " << i;
    EXPECT_LE(on.mesh.num_cells(), off.mesh.num_cells()) << "mesh " << i;
    fine += off.mesh.num_cells();
    coarse += on.mesh.num_cells();
    if (method != OptimParams::Method::None) continue;
    merged_unoptimised += on.mesh.num_cells() < off.mesh.num_cells();
    // Points at their barycentres in both: the same volume per vertex.
    const auto a = vertex_volumes(off.mesh), b = vertex_volumes(on.mesh);
    ASSERT_EQ(a.size(), b.size()) << "mesh " << i;
    for (const auto& [v, vol] : a)
      EXPECT_NEAR(b.at(v), vol, 1e-12 * (1 + std::abs(vol))) << "mesh " << i << " vertex " << v;
  }
  // Not vacuous: corners were merged, also where the volumes were compared.
  EXPECT_LT(coarse, fine);
  EXPECT_GT(merged_unoptimised, 0u);
}

TEST(SplitCoarsen, SameOutputForAnyThreadCount) {
  for (int i = 1; i < 4; ++i) {
    const TetSoup soup = random_classified_mesh(coarsen_mesh(i));
    ConvertResult one, two;
    {
      tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
      one = run(soup, OptimParams::Method::Local, true);
    }
    {
      tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
      two = run(soup, OptimParams::Method::Local, true);
    }
    ASSERT_EQ(one.mesh.num_cells(), two.mesh.num_cells()) << "mesh " << i;
    ASSERT_EQ(one.mesh.points.size(), two.mesh.points.size()) << "mesh " << i;
    for (std::size_t p = 0; p < one.mesh.points.size(); ++p)
      ASSERT_TRUE(one.mesh.points[p] == two.mesh.points[p]) << "mesh " << i << " point " << p;
    EXPECT_EQ(one.mesh.face_points, two.mesh.face_points) << "mesh " << i;
  }
}

}  // namespace
}  // namespace polydual
