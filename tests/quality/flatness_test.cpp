// Face flatness (quality/flatness.h) on faces whose answer is known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "generate/hex_block.h"
#include "quality/flatness.h"

namespace polydual {
namespace {

TEST(Flatness, PlanarFacesAreFlat) {
  const std::vector<Point3> square = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  EXPECT_DOUBLE_EQ(face_flatness(square).flatness, 1.0);
  EXPECT_EQ(face_flatness(square).deviation, 0.0);
  // A tilted planar hexagon (not axis-aligned): flat up to rounding.
  std::vector<Point3> hex;
  for (int i = 0; i < 6; ++i) {
    const double a = i * M_PI / 3, x = std::cos(a), y = std::sin(a);
    hex.push_back({x, 0.6 * y, 0.8 * y + 0.3 * x});  // in the plane through 0 spanned by (1,0,.3), (0,.6,.8)
  }
  EXPECT_NEAR(face_flatness(hex).flatness, 1.0, 1e-14);
  EXPECT_NEAR(face_flatness(hex).deviation, 0.0, 1e-14);
  const std::vector<Point3> tri = {{0.1, 0.2, 0.3}, {1.7, -0.4, 0.9}, {0.3, 2.1, -1.2}};
  EXPECT_NEAR(face_flatness(tri).flatness, 1.0, 1e-15);
  EXPECT_NEAR(face_flatness(tri).deviation, 0.0, 1e-15);
}

TEST(Flatness, SaddleQuadHasTheClosedFormValues) {
  // (1,0,h), (0,1,-h), (-1,0,h), (0,-1,-h): centre 0, area vector (0,0,2), four
  // fan triangles of area sqrt(1+2h^2)/2: flatness 1/sqrt(1+2h^2). Best-fit
  // plane z = 0 (scatter diag(2,2,4h^2), h < 1/sqrt 2), deviation h / diameter 2.
  for (double h : {0.1, 0.5}) {
    const std::vector<Point3> q = {{1, 0, h}, {0, 1, -h}, {-1, 0, h}, {0, -1, -h}};
    const FaceFlatness f = face_flatness(q);
    EXPECT_NEAR(f.flatness, 1 / std::sqrt(1 + 2 * h * h), 1e-15) << h;
    EXPECT_NEAR(f.deviation, h / 2, 1e-15) << h;
  }
}

TEST(Flatness, MeshStatistics) {
  PolyMesh m = hex_block(3);
  FlatnessStats st = flatness_stats(m);
  EXPECT_EQ(st.faces, m.num_faces());
  EXPECT_DOUBLE_EQ(st.min_flatness, 1.0);
  EXPECT_EQ(st.warped, 0u);
  EXPECT_EQ(st.max_deviation, 0.0);
  m.points[(1 * 4 + 1) * 4 + 1].z += 0.6;  // an interior point lifted: its faces warp
  st = flatness_stats(m);
  EXPECT_LT(st.min_flatness, 0.99);
  EXPECT_GT(st.max_deviation, 0.01);
  EXPECT_LT(st.mean_flatness, 1.0);
  EXPECT_GT(st.mean_deviation, 0.0);
  const Json j = st.to_json();
  EXPECT_NE(j.find("min"), nullptr);
  EXPECT_NE(j.find("max_plane_deviation"), nullptr);
}

}  // namespace
}  // namespace polydual
