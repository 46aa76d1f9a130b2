// Gmsh files as the real gmsh binary writes them: the models of
// tests/data/geo are meshed at test time (skipped when gmsh is not installed)
// in every layout a user may save (msh 4.1 / 2.2, ASCII / binary, with and
// without -save_all, -order 2, -part 2), read, and classified. Each variant
// must give the model classification of the plain msh 4.1 -save_all file.
// The committed files of tests/data/gmsh (made by the same commands, see
// tests/data/gmsh/README) are read without gmsh.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "classify/classify.h"
#include "core/error.h"
#include "io/msh_reader.h"
#include "require_tool.h"

namespace polydual {
namespace {

using testing::HasSubstr;
namespace fs = std::filesystem;

const std::string kData = POLYDUAL_TEST_DATA;

bool have_gmsh() {
  static const bool have = test::have_command("gmsh");
  return have;
}

// A scratch directory removed at exit.
struct ScratchDir {
  fs::path path = fs::path(testing::TempDir()) / ("polydual_gmsh_" + std::to_string(getpid()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() { fs::remove_all(path); }
};

// Meshes tests/data/geo/<model>.geo with `options`; returns the .msh path.
std::string gmsh(const std::string& model, const std::string& options) {
  static const ScratchDir scratch;
  const fs::path& dir = scratch.path;
  std::string name = model + options;
  for (char& c : name)
    if (c == ' ' || c == '-') c = '_';
  const std::string out = (dir / (name + ".msh")).string();
  const std::string cmd = "gmsh -3 " + kData + "/geo/" + model + ".geo " + options + " -o " + out + " > " + out +
                          ".log 2>&1";
  if (std::system(cmd.c_str()) != 0) ADD_FAILURE() << "failed: " << cmd;
  return out;
}

struct Counts {
  std::size_t tets, faces, edges, vertices;
  bool operator==(const Counts&) const = default;
};
std::ostream& operator<<(std::ostream& os, const Counts& c) {
  return os << c.tets << " tets, model: " << c.faces << " faces, " << c.edges << " edges, " << c.vertices
            << " vertices";
}

Counts classified(const TetSoup& s) {
  try {
    const ClassifiedTetMesh m = classify(s);
    return {m.num_tets(), m.model().count(2), m.model().count(1), m.model().count(0)};
  } catch (const InputError& e) {
    ADD_FAILURE() << "classify rejected " << s.source << ": " << e.what();
    return {};
  }
}

TetSoup read(const std::string& path) {
  try {
    return read_msh_file(path);
  } catch (const InputError& e) {
    ADD_FAILURE() << e.what();
    return {};
  }
}

bool has_warning(const TetSoup& s, const std::string& part) {
  for (const std::string& w : s.warnings)
    if (w.find(part) != std::string::npos && w.rfind(s.source, 0) == 0) return true;
  return false;
}

// The layouts that must all read to the reference classification.
const char* const kSameModel[] = {"-format msh4 -save_all -bin", "-format msh2 -save_all",
                                  "-format msh2 -save_all -bin", "-format msh4 -save_all -order 2",
                                  "-format msh2 -save_all -order 2", "-format msh4 -save_all -part 2",
                                  "-format msh4 -save_all -part 2 -bin", "-format msh4 -save_all -part 2 -part_ghosts"};

void expect_every_layout(const std::string& model, const Counts& expected) {
  const TetSoup ref = read(gmsh(model, "-format msh4 -save_all"));
  EXPECT_EQ(classified(ref), expected) << model;
  EXPECT_TRUE(ref.full_classification) << model;
  for (const char* options : kSameModel) {
    const TetSoup s = read(gmsh(model, options));
    EXPECT_EQ(classified(s), expected) << model << " " << options;
    EXPECT_EQ(s.tets.size(), ref.tets.size()) << model << " " << options;
    const std::string opt(options);
    if (opt.find("-order 2") != std::string::npos)
      EXPECT_TRUE(has_warning(s, "second-order elements: using their corner vertices")) << options;
    if (opt.find("-part") != std::string::npos) {
      EXPECT_TRUE(has_warning(s, "partitioned mesh (2 partitions) read as one")) << options;
      EXPECT_TRUE(s.full_classification) << options;
      EXPECT_EQ(s.ignored.points, ref.ignored.points) << options;
      EXPECT_EQ(s.ignored.curves, ref.ignored.curves) << options;
      EXPECT_EQ(s.ignored.surfaces, ref.ignored.surfaces) << options;
    }
  }
}

#define REQUIRE_GMSH() \
  if (!have_gmsh()) POLYDUAL_MISSING_TOOL("gmsh is not installed (Debian package gmsh)")

TEST(IoGmsh, BoxWithHoleDropsConstructionPointAndFreeCurve) {
  REQUIRE_GMSH();
  const TetSoup s = read(gmsh("hole", "-format msh4 -save_all"));
  // The circle centres (point 1 and its extruded copy) and the free line 100
  // with its two points.
  EXPECT_EQ(s.ignored.points, 4u);
  EXPECT_EQ(s.ignored.curves, 1u);
  EXPECT_EQ(s.ignored.surfaces, 0u);
  EXPECT_GE(s.ignored.elements, 4u);  // 3 points and the line's segments
  EXPECT_TRUE(has_warning(s, "not attached to the tets"));
  for (const TaggedVertex& c : s.corners) EXPECT_NE(c.tag, 1);
  // 4 box sides, 4 hole quarters, top and bottom; 24 curves; 16 points.
  expect_every_layout("hole", {s.tets.size(), 10, 24, 16});
}

TEST(IoGmsh, SphereWithCollapsedPoleCurves) {
  REQUIRE_GMSH();
  const TetSoup s = read(gmsh("sphere", "-format msh4 -save_all"));
  EXPECT_EQ(s.ignored.curves, 2u);  // the two pole curves have no element
  EXPECT_TRUE(s.full_classification);
  expect_every_layout("sphere", {s.tets.size(), 1, 1, 2});
}

TEST(IoGmsh, SheetLargerThanTheBoxKeepsItsInsidePart) {
  REQUIRE_GMSH();
  const TetSoup s = read(gmsh("sheet", "-format msh4 -save_all"));
  EXPECT_EQ(s.ignored.surfaces, 1u);  // the frame of the sheet outside the box
  EXPECT_GE(s.ignored.curves, 4u);
  const Counts c = classified(s);
  // The sheet cuts the box in two volumes: 10 box face pieces (4 sides cut
  // in two) + the inside part of the sheet, now their interface.
  expect_every_layout("sheet", {s.tets.size(), 11, c.edges, c.vertices});
  EXPECT_EQ(c.edges, 20u);
}

TEST(IoGmsh, TwoVolumesWithPhysicalGroups) {
  REQUIRE_GMSH();
  const TetSoup s = read(gmsh("twovol", "-format msh4 -save_all"));
  ASSERT_EQ(s.groups.size(), 4u);
  EXPECT_EQ(s.groups[0].name, "interface");
  EXPECT_EQ(s.groups[0].dim, 2);
  EXPECT_EQ(s.groups[0].entities, std::vector<std::int32_t>{2});
  EXPECT_EQ(s.groups[1].name, "ends");
  EXPECT_EQ(s.groups[1].entities, (std::vector<std::int32_t>{1, 7}));
  EXPECT_EQ(s.groups[2].name, "left");
  EXPECT_EQ(s.groups[2].dim, 3);
  EXPECT_EQ(s.groups[2].entities, std::vector<std::int32_t>{s.groups[2].tag});  // regions are physical tags
  EXPECT_EQ(s.groups[3].name, "right");
  expect_every_layout("twovol", {s.tets.size(), 11, 20, 12});
  // msh 2.2 groups come from the physical tags its elements carry; with
  // -save_all Gmsh writes physical tag 0 everywhere, so only the names remain.
  const TetSoup v2 = read(gmsh("twovol", "-format msh2"));
  ASSERT_EQ(v2.groups.size(), 4u);
  EXPECT_EQ(v2.groups[2].name, "left");
  EXPECT_EQ(v2.groups[2].entities, std::vector<std::int32_t>{v2.groups[2].tag});
  EXPECT_EQ(v2.groups[0].name, "interface");
  EXPECT_EQ(v2.groups[0].entities, std::vector<std::int32_t>{v2.groups[0].tag});
  EXPECT_EQ(classified(v2).faces, 11u);
  const TetSoup v2_all = read(gmsh("twovol", "-format msh2 -save_all"));
  ASSERT_EQ(v2_all.groups.size(), 4u);
  EXPECT_TRUE(v2_all.groups[2].entities.empty());
}

TEST(IoGmsh, PhysicalGroupsOnlyReadWhatIsThere) {
  REQUIRE_GMSH();
  // Without -save_all only the physical groups' elements are written: the
  // boundary faces of neither group are missing, so the classification is
  // completed from the tets and gives the same model.
  const TetSoup full = read(gmsh("twovol", "-format msh4 -save_all"));
  const TetSoup s = read(gmsh("twovol", "-format msh4"));
  EXPECT_FALSE(s.full_classification);
  EXPECT_TRUE(has_warning(s, "with no element in the file (Gmsh without -save_all writes only physical groups)"));
  EXPECT_EQ(s.tets.size(), full.tets.size());
  EXPECT_EQ(classified(s).faces, 11u);
  // A volume in no physical group: its tets are not in the file.
  const TetSoup one = read(gmsh("onephys", "-format msh4"));
  EXPECT_TRUE(has_warning(one, "1 volume, 11 surfaces and 20 curves with no element in the file"));
  EXPECT_TRUE(has_warning(one, "the tets of those volumes are missing from the mesh"));
  EXPECT_EQ(classified(one).tets * 2, full.tets.size() + (classified(one).tets * 2 - full.tets.size()));
  const TetSoup one_all = read(gmsh("onephys", "-format msh4 -save_all"));
  EXPECT_LT(one.tets.size(), one_all.tets.size());
  EXPECT_EQ(classified(one).faces, 6u);  // a lone box
}

// The committed files of tests/data/gmsh, read without gmsh.
TEST(IoGmsh, CommittedFiles) {
  const std::string dir = kData + "/gmsh/";
  const TetSoup sheet = read(dir + "sheet_save_all.msh");
  EXPECT_EQ(sheet.ignored.surfaces, 1u);
  EXPECT_EQ(classified(sheet).faces, 11u);
  const TetSoup sphere = read(dir + "sphere_order2_bin.msh");
  EXPECT_TRUE(has_warning(sphere, "second-order elements"));
  EXPECT_EQ(classified(sphere).faces, 1u);
  const TetSoup physical = read(dir + "twovol_v2_physical_bin.msh");
  ASSERT_EQ(physical.groups.size(), 4u);
  EXPECT_EQ(physical.groups[2].name, "left");
  EXPECT_EQ(classified(physical).faces, 11u);
  const TetSoup part = read(dir + "twovol_part2.msh");
  EXPECT_TRUE(has_warning(part, "partitioned mesh (2 partitions) read as one"));
  EXPECT_TRUE(part.full_classification);
  EXPECT_EQ(classified(part), (Counts{part.tets.size(), 11, 20, 12}));
  const TetSoup hole = read(dir + "hole_v2_save_all.msh");
  EXPECT_EQ(hole.ignored.points, 4u);
  EXPECT_EQ(classified(hole), (Counts{hole.tets.size(), 10, 24, 16}));
}

}  // namespace
}  // namespace polydual
