// Smoothing of a surface dual (optim/surface_smooth.h): better worst fan
// triangle, every polygon still valid by the exact test, points kept on
// their cells' planes, the area identity kept.
#include <gtest/gtest.h>

#include "classify/classify_primal.h"
#include "dual/surface_dual.h"
#include "generate/fracture_surfaces.h"
#include "mesh/cell_soup.h"
#include "optim/surface_smooth.h"
#include "quality/surface_verdict.h"

using namespace polydual;

namespace {

// Shifts every cell centre towards its cell's first vertex by `t` of the
// way; returns how many polygons stayed valid (all, for small t).
void pull_centres(PolySurface& s, const PrimalMesh& m, double t) {
  for (std::size_t p = 0; p < s.num_points(); ++p) {
    if (s.point_origin(p).kind != SurfacePointOrigin::Kind::CellCentre) continue;
    const Point3 a = m.point(m.cell_vertices(PrimalCellId(std::size_t(s.point_origin(p).id)))[0]);
    s.set_point(p, s.point(p) + t * (a - s.point(p)));
  }
}

}  // namespace

TEST(SurfaceSmooth, ImprovesTheWorstFanTriangleAndKeepsEveryPolygonValid) {
  const PrimalMesh m = build_primal(cell_soup(fracture_network_surface(8)));
  PolySurface s = build_surface_dual(m);
  pull_centres(s, m, 0.3);
  ASSERT_EQ(surface_verdicts(s).invalid, 0u);
  const SurfaceSmoothReport r = smooth_surface(s, m, {4});
  EXPECT_GT(r.moved, 100u);
  EXPECT_GT(r.min_quality_after, r.min_quality_before + 0.05);
  EXPECT_EQ(surface_verdicts(s).invalid, 0u);
  EXPECT_LE(surface_area_identity(m, s).max_rel_error, 1e-12);
  // Axis planes: the projection on a cell's plane keeps the coordinate exactly.
  for (std::size_t p = 0; p < s.num_points(); ++p) {
    if (s.point_origin(p).kind != SurfacePointOrigin::Kind::CellCentre) continue;
    const PrimalCellId c(std::size_t(s.point_origin(p).id));
    if (m.cell_class(c).tag == 1) EXPECT_EQ(s.point(p).z, 0.0);
    if (m.cell_class(c).tag == 3) EXPECT_EQ(s.point(p).y, 0.5);
  }
}

TEST(SurfaceSmooth, UntanglesAPolygonAndNeverAcceptsAnInvalidOne) {
  const PrimalMesh m = build_primal(cell_soup(lattice_rectangles_soup({{2, 0, 0, 0, 16, 0, 16, 1}}, 8, "<sq>")));
  PolySurface s = build_surface_dual(m);
  // Reflect one interior centre through a vertex of its polygon: invalid.
  std::size_t poly = 0;
  while (m.vertex_class(VertexId(std::size_t(s.primal_vertex(poly)))).dim != 2) ++poly;
  const std::uint32_t q = s.polygon(poly)[0];
  s.set_point(q, 2.0 * s.reference(poly) - s.point(q));
  const std::size_t invalid = surface_verdicts(s).invalid;
  ASSERT_GT(invalid, 0u);
  smooth_surface(s, m, {8});
  EXPECT_LT(surface_verdicts(s).invalid, invalid);
  // Zero sweeps: nothing moves.
  PolySurface t = build_surface_dual(m);
  const auto before = t.points();
  EXPECT_EQ(smooth_surface(t, m, {0}).moved, 0u);
  EXPECT_EQ(t.points(), before);
}
