// On a Delaunay mesh, the dual face of an interior edge whose tets are all
// well-centred is a Voronoi face: its points are the tets' circumcentres, all
// equidistant from the edge's endpoints, so the face is planar and
// perpendicular to the edge (design §4, paper §2.1).
#include <gtest/gtest.h>

#include <map>

#include "classify/classify.h"
#include "dual/build_dual.h"
#include "dual/central_points.h"
#include "generate/random_mesh.h"

using namespace polydual;

TEST(DualVoronoi, WellCentredInteriorFacesArePerpendicularBisectors) {
  std::size_t checked = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 150;
    ClassifiedTetMesh m = classify(random_classified_mesh(p));  // CGAL Delaunay
    DualParams dp;
    dp.cleanup = false;  // keep one point per tet
    PolyMesh pm = build_dual(m, dp);
    // Index dual faces by their sorted point coordinates.
    std::map<std::vector<std::array<double, 3>>, FaceId> by_points;
    for (std::size_t f = 0; f < pm.num_faces(); ++f) {
      std::vector<std::array<double, 3>> key;
      for (PointId q : pm.face(FaceId(f))) key.push_back({pm.points[q.idx].x, pm.points[q.idx].y, pm.points[q.idx].z});
      std::sort(key.begin(), key.end());
      by_points[key] = FaceId(f);
    }
    for (std::size_t e = 0; e < m.num_edges(); ++e) {
      bool closed;
      std::vector<TetId> ring = m.edge_ring(EdgeId(e), &closed);
      if (!closed || m.edge_class(EdgeId(e)).dim != 3) continue;
      const Point3 a = m.point(m.edge(EdgeId(e))[0]), b = m.point(m.edge(EdgeId(e))[1]);
      std::vector<std::array<double, 3>> key;
      bool all_wc = true;
      for (TetId t : ring) {
        const auto& v = m.tet(t);
        CentralPoint c = tet_central_point(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3]));
        all_wc = all_wc && c.well_centred;
        key.push_back({c.p.x, c.p.y, c.p.z});
      }
      if (!all_wc) continue;
      std::sort(key.begin(), key.end());
      ASSERT_TRUE(by_points.count(key)) << "no dual face for interior edge " << e;
      const FaceId f = by_points[key];
      // Owner is the side of edge(e)[0], and the loop turns right-handedly about a->b.
      EXPECT_EQ(pm.cell_primal[pm.face_owner[f.idx].idx], VertexId(m.input_vertex(m.edge(EdgeId(e))[0])));
      const double len = norm(b - a);
      Vec3 normal{};
      auto loop = pm.face(f);
      for (std::size_t k = 0; k < loop.size(); ++k)
        normal += cross(pm.points[loop[k].idx], pm.points[loop[(k + 1) % loop.size()].idx]);
      EXPECT_GT(dot(normal, b - a), 0.0);
      for (PointId q : loop) {
        const Point3 c = pm.points[q.idx];
        // equidistant from a and b: on the bisector plane, perpendicular to ab
        EXPECT_NEAR(norm(c - a), norm(c - b), 1e-9 * len);
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 50u);
}
