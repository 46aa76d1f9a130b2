// Write then read gives the same points (bit for bit), tets, regions and, as
// far as each format carries them, the same tagged triangles, edges and corners.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

#include "core/error.h"
#include "io/msh_reader.h"
#include "io/read_tet_mesh.h"
#include "io/write_tet_mesh.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;

// A soup with awkward numbers: coordinates that are not short decimals,
// region tags 0 and negative, and every kind of classification.
TetSoup awkward_soup() {
  TetSoup s = read_msh_file(std::string(POLYDUAL_TEST_DATA) + "/cube5.msh");
  for (Point3& p : s.points) p = {p.x / 3.0 + 0.1, p.y * 1e-7 - 1e5, p.z * 2.0 / 7.0};
  s.tet_region = {0, -4, 0, 12345, 7};
  s.triangles[0].tag = 42;
  return s;
}

class IoRoundTrip : public testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("polydual_io_rt_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_P(IoRoundTrip, SamePointsTetsAndTags) {
  const std::string ext = GetParam();
  const TetSoup a = awkward_soup();
  const std::string path = (dir_ / ("out" + ext)).string();
  write_tet_mesh(a, path);
  const TetSoup b = read_tet_mesh(path);
  ASSERT_EQ(b.points.size(), a.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(b.points[i], a.points[i]) << i;
  EXPECT_EQ(b.tets, a.tets);
  EXPECT_EQ(b.tet_region, a.tet_region);
  // msh groups elements by entity, so compare triangles as sorted multisets.
  auto tris = [](const TetSoup& s) {
    std::vector<std::pair<std::int32_t, std::array<std::uint32_t, 3>>> r;
    for (const auto& t : s.triangles) r.emplace_back(t.tag, t.v);
    std::sort(r.begin(), r.end());
    return r;
  };
  EXPECT_EQ(tris(b), tris(a));
  if (ext == ".msh") {
    EXPECT_EQ(b.edges.size(), a.edges.size());
    EXPECT_EQ(b.corners.size(), a.corners.size());
    EXPECT_TRUE(b.full_classification);
  }
  if (ext == ".mesh") {
    EXPECT_EQ(b.edges.size(), a.edges.size());
    EXPECT_EQ(b.corners.size(), a.corners.size());
  }
  // Atomic writes leave no temporaries behind.
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_THAT(entry.path().string(), testing::Not(testing::HasSubstr(".tmp.")));
}

INSTANTIATE_TEST_SUITE_P(Formats, IoRoundTrip, testing::Values(".msh", ".mesh", ".node", ".vtu"),
                         [](const auto& info) { return std::string(info.param + 1); });

TEST(IoRoundTripMisc, MshWithoutTrianglesIsNotFullyClassified) {
  TetSoup a = awkward_soup();
  a.triangles.clear();
  const fs::path path = fs::temp_directory_path() / ("polydual_io_nt_" + std::to_string(::getpid()) + ".msh");
  write_tet_mesh(a, path.string());
  const TetSoup b = read_tet_mesh(path.string());
  fs::remove(path);
  EXPECT_FALSE(b.full_classification);
  EXPECT_EQ(b.tet_region, a.tet_region);
}

TEST(IoRoundTripMisc, UnknownExtensionIsAUsageError) {
  EXPECT_THROW(write_tet_mesh(awkward_soup(), "/tmp/x.stl"), UsageError);
}

}  // namespace
}  // namespace polydual
