// Tests of the optimiser's gates beside the exact star test (optim/foam_gate.h,
// optim/context.h): OpenFOAM's centres, its face-pyramid and face-tet checks,
// that the optimiser keeps the cells that pass them passing, that the worst
// valid cell never gets worse, and the report of the cells above the bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "generate/hex_block.h"
#include "optim/foam_gate.h"
#include "optim/optimize.h"
#include "quality/metrics.h"
#include "quality/star_verdict.h"
#include "quality/stencil.h"
#include "raw_random_dual.h"

namespace polydual {
namespace {

std::vector<PointId> ids(std::size_t n) {
  std::vector<PointId> v;
  for (std::size_t i = 0; i < n; ++i) v.push_back(PointId(i));
  return v;
}

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-14) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// A planar polygon's OpenFOAM centre is its centroid and its area vector its
// area times the normal: a unit square with a roof (apex (0.5, 1.5)) has
// area 1.25 and centroid y = (0.5 x 1 + 7/6 x 0.25) / 1.25.
TEST(FoamGate, FaceCentreIsTheCentroidOfAPlanarPolygon) {
  const std::vector<Point3> pts{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 1.5, 0}, {0, 1, 0}};
  Vec3 area;
  const Point3 c = foam_face_centre(ids(5), pts, &area);
  expect_near(c, {0.5, (0.5 + 7.0 / 6.0 * 0.25) / 1.25, 0});
  expect_near(area, {0, 0, 1.25});
  const std::vector<Point3> tri{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  const Point3 t = foam_face_centre(ids(3), tri, &area);
  expect_near(t, {2.0 / 3.0, 1.0 / 3.0, 0});
  expect_near(area, {0, 0, 1});
}

// A unit cube's OpenFOAM cell centre is its middle; stretching one corner
// moves it towards that corner.
TEST(FoamGate, CellCentreOfACube) {
  PolyMesh m = hex_block(1);
  MeshStencil s = build_stencil(m);
  expect_near(foam_cell_centre(s, 0, m.points), {0.5, 0.5, 0.5});
  for (Point3& p : m.points)
    if (p.x == 1 && p.y == 1 && p.z == 1) p = {1.5, 1.5, 1.5};
  const Point3 c = foam_cell_centre(s, 0, m.points);
  EXPECT_GT(c.x, 0.5);
  EXPECT_NEAR(c.x, c.y, 1e-14);
  EXPECT_NEAR(c.y, c.z, 1e-14);
}

// A regular block passes every check; the middle point of a 2x2x2 block
// pushed far out through a corner of the block makes faces whose pyramids
// and tets OpenFOAM calls wrongly oriented.
TEST(FoamGate, CheckFindsWronglyOrientedPyramidsAndTets) {
  PolyMesh m = hex_block(2);
  const FoamCheck ok = foam_check(m);
  EXPECT_EQ(ok.pyramid_faces, 0u);
  EXPECT_EQ(ok.face_tet_faces, 0u);
  EXPECT_TRUE(ok.cells.empty());
  std::size_t mid = m.num_points();
  for (std::size_t i = 0; i < m.num_points(); ++i)
    if (m.points[i] == Point3{1, 1, 1}) mid = i;
  ASSERT_LT(mid, m.num_points());
  m.points[mid] = {1.9, 1.9, 1.9};
  const FoamCheck bad = foam_check(m);
  EXPECT_GT(bad.face_tet_faces, 0u);
  EXPECT_GT(bad.pyramid_faces, 0u);
  EXPECT_FALSE(bad.cells.empty());
  // The cell at the far corner holds the point: it fails.
  EXPECT_TRUE(std::find(bad.cells.begin(), bad.cells.end(), 7u) != bad.cells.end() ||
              std::find(bad.cells.begin(), bad.cells.end(), 0u) != bad.cells.end());
}

// The exact maximum over the given cells' qualities.
double max_quality(const MeshStencil& s, const PolyMesh& m, const std::vector<char>& which) {
  double w = 0;
  for (std::uint32_t c = 0; c < s.num_cells(); ++c)
    if (which[c]) w = std::max(w, cell_quality(s, c, Metric::Q1, m.points));
  return w;
}

// Perturbed hex blocks (every cell valid): the default local scheme leaves
// no cell above the worst cell before it (each sweep caps its moves at the
// worst valid cell of its start). With a point pushed through its
// neighbours (tangled): the records' max never rises from a sweep that
// started with every cell valid.
TEST(OptimGates, TheWorstValidCellNeverGetsWorse) {
  for (unsigned seed : {1u, 2u, 3u}) {
    PolyMesh m = hex_block(4);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    for (std::size_t i = 0; i < m.num_points(); ++i)
      if (m.point_class[i].dim == 3) m.points[i] += Vec3{u(rng), u(rng), u(rng)};
    const MeshStencil s = build_stencil(m);
    const std::vector<char> all(m.num_cells(), 1);
    const double before = max_quality(s, m, all);
    const OptimReport rep = optimize(m, nullptr, OptimParams{});
    ASSERT_EQ(rep.invalid_before, 0) << "seed " << seed;
    EXPECT_LE(max_quality(s, m, all), before * (1 + 1e-12)) << "seed " << seed;
    EXPECT_LT(rep.after.mean, rep.before.mean) << "seed " << seed;  // it did smooth
  }
  int checked = 0;
  for (unsigned seed : {1u, 2u, 3u}) {
    PolyMesh m = hex_block(4);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    for (std::size_t i = 0; i < m.num_points(); ++i)
      if (m.point_class[i].dim == 3) m.points[i] += Vec3{u(rng), u(rng), u(rng)};
    m.points[(1 * 5 + 1) * 5 + 1] = {2.4, 1.3, 0.9};  // pushed through its neighbours: tangled
    const OptimReport rep = optimize(m, nullptr, OptimParams{});
    ASSERT_GT(rep.invalid_before, 0) << "seed " << seed;
    for (std::size_t i = 1; i < rep.iterations.size(); ++i)
      if (rep.iterations[i - 1].invalid == 0) {
        ++checked;
        EXPECT_LE(rep.iterations[i].max_quality, rep.iterations[i - 1].max_quality * (1 + 1e-12))
            << "seed " << seed << " record " << i;
      }
  }
  EXPECT_GT(checked, 0);
}

// Random classified meshes' raw duals (tangled), one sweep at a time: no
// cell valid before a sweep ends above the worst valid cell before it.
TEST(OptimGates, NoSweepRaisesTheWorstValidCell) {
  for (std::uint64_t seed : {1u, 2u}) {
    ConvertResult r = raw_random_conversion(seed, 150);
    PolyMesh& m = r.mesh;
    const ModelFacets facets = model_facets(r.primal);
    const MeshStencil s = build_stencil(m);
    for (int sweep = 0; sweep < 6; ++sweep) {
      const auto v = star_shaped_verdicts(m);
      std::vector<char> valid(v.size());
      for (std::size_t c = 0; c < v.size(); ++c) valid[c] = v[c].valid;
      const double before = max_quality(s, m, valid);
      OptimParams p;
      p.max_iter = 1;
      p.foam_gate = false;  // one sweep and nothing after it (the repair is a stage of its own)
      optimize(m, &facets, p);
      EXPECT_LE(max_quality(s, m, valid), before * (1 + 1e-12)) << "seed " << seed << " sweep " << sweep;
    }
  }
}

// The gate keeps OpenFOAM's verdict: with it on every move, the optimised random duals
// have no more faces that OpenFOAM rejects than they had, and no cell fails
// the gate that passed it; the report counts the cells failing it.
TEST(OptimGates, TheOptimiserKeepsOpenFoamsChecksPassing) {
  std::size_t failing_before = 0, failing_after = 0;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    ConvertResult r = raw_random_conversion(seed, 150);
    const FoamCheck before = foam_check(r.mesh);
    OptimParams p;
    p.foam_gate_sweeps = true;  // the gate on every move: the guarantee below
    const ModelFacets facets = model_facets(r.primal);
    const OptimReport rep = optimize(r.mesh, &facets, p);
    const FoamCheck after = foam_check(r.mesh);
    EXPECT_LE(after.face_tet_faces, before.face_tet_faces) << "seed " << seed;
    EXPECT_LE(after.pyramid_faces, before.pyramid_faces) << "seed " << seed;
    EXPECT_LE(rep.foam_failing_after, rep.foam_failing_before) << "seed " << seed;
    EXPECT_EQ(rep.foam_failing_cells.size(), rep.foam_failing_after) << "seed " << seed;
    failing_before += rep.foam_failing_before;
    failing_after += rep.foam_failing_after;
    const Json j = rep.to_json();
    EXPECT_NE(j.find("foam_failing_after"), nullptr);
  }
  EXPECT_GT(failing_before, 0u);  // the raw duals are tangled: the gate had work
  EXPECT_LT(failing_after, failing_before);
}

// A cell left above the bound is listed with its pinned points and their
// model entities (no primal: every boundary point is pinned).
TEST(OptimGates, WorstCellsNameTheirPinnedPoints) {
  PolyMesh m = hex_block(2, 1.0, true);
  std::size_t corner = m.num_points();
  for (std::size_t i = 0; i < m.num_points(); ++i)
    if (m.points[i] == Point3{2, 2, 2}) corner = i;
  ASSERT_LT(corner, m.num_points());
  m.points[corner] = {2.0, 2.0, 40.0};  // a needle of a corner cell, still star-shaped
  OptimParams p;
  p.max_iter = 0;
  const OptimReport rep = optimize(m, nullptr, p);
  ASSERT_FALSE(rep.worst_cells.empty());
  EXPECT_GE(rep.cells_above_bound, rep.worst_cells.size());
  for (std::size_t i = 1; i < rep.worst_cells.size(); ++i)
    EXPECT_GE(rep.worst_cells[i - 1].quality, rep.worst_cells[i].quality);
  const WorstCell& w = rep.worst_cells.front();
  EXPECT_GT(w.quality, OptimReport::kWorstBound);
  bool names_corner = false;
  for (const auto& [q, model] : w.pinned) {
    EXPECT_EQ(model, m.point_class[q.idx]);
    names_corner |= q.idx == corner && model.dim == 0;
  }
  EXPECT_TRUE(names_corner);
  const Json j = rep.to_json();
  ASSERT_NE(j.find("worst_cells"), nullptr);
}

}  // namespace
}  // namespace polydual
