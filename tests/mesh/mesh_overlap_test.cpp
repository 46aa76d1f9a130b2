// Input tet meshes that cover a place twice or hold a crack are refused by
// classify() (classify/self_overlap.h, proofs/self_overlap.md L15), with the
// file, the place and the reason; legitimate meshes that touch themselves
// (cubes sharing an edge or a corner, a part inside a cavity, fractures and
// fins, every built-in domain) are accepted. Also the exact tests behind it
// (classify/triangle_crossing.h, the predicates orient2d and
// orient3d_centroid) on hand-made configurations.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>

#include "classify/classify.h"
#include "classify/self_overlap.h"
#include "classify/triangle_crossing.h"
#include "core/error.h"
#include "generate/domains.h"
#include "generate/random_mesh.h"
#include "io/medit_io.h"
#include "predicates/predicates.h"
#include "run_command.h"

namespace polydual {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Contains;

// The lattice cube [0, n h]^3 of Kuhn tets moved by `shift`.
TetSoup cube(int n, double h, Point3 shift) {
  TetSoup s = kuhn_lattice(n, n, n, h, h, h);
  for (Point3& p : s.points) p += shift;
  s.source = "cubes";
  return s;
}

// b's points and tets appended to a's (b's vertex and tet numbers shifted).
TetSoup join(TetSoup a, const TetSoup& b) {
  const auto nv = std::uint32_t(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (auto t : b.tets) {
    for (auto& v : t) v += nv;
    a.tets.push_back(t);
  }
  a.tet_region.insert(a.tet_region.end(), b.tet_region.begin(), b.tet_region.end());
  return a;
}

// The tets of s whose centroid satisfies keep (unused points stay: classify drops them).
TetSoup keep_tets(TetSoup s, const std::function<bool(const Point3&)>& keep) {
  TetSoup out = s;
  out.tets.clear();
  out.tet_region.clear();
  for (std::size_t t = 0; t < s.tets.size(); ++t) {
    Point3 c{};
    for (auto v : s.tets[t]) c += 0.25 * s.points[v];
    if (!keep(c)) continue;
    out.tets.push_back(s.tets[t]);
    out.tet_region.push_back(s.tet_region[t]);
  }
  return out;
}

// The message of the InputError classify() throws, or "accepted".
std::string refusal(const TetSoup& s) {
  try {
    classify(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

// The tet numbers a message names after "tet " / "tets " (in order).
std::vector<int> tets_named(const std::string& msg) {
  std::vector<int> out;
  const std::regex re("tets? ([0-9]+)( and ([0-9]+))?");
  for (auto it = std::sregex_iterator(msg.begin(), msg.end(), re); it != std::sregex_iterator(); ++it) {
    out.push_back(std::stoi((*it)[1]));
    if ((*it)[3].matched) out.push_back(std::stoi((*it)[3]));
  }
  return out;
}

// ---- refused

TEST(MeshOverlap, TwoIdenticalCopiesAreRefused) {
  const TetSoup one = cube(2, 1.0, {0, 0, 0});  // 27 vertices, 48 tets
  const std::string msg = refusal(join(one, one));
  // Vertex 1 (0,0,0) and its copy 28; tet 1 uses vertex 1, tet 49 its copy.
  EXPECT_THAT(msg, AllOf(HasSubstr("cubes: vertex 1: vertices 1 and 28 are at the same position (0, 0, 0)"),
                         HasSubstr("use vertex 1 and"), HasSubstr("use vertex 28"),
                         HasSubstr("overlaps itself or holds a crack")))
      << msg;
}

TEST(MeshOverlap, CopiesShiftedByHalfAreRefused) {
  // Shifted by half the cube along x, and off the lattice in y and z (no
  // vertex coincides): the boundaries cross.
  const TetSoup one = cube(2, 1.0, {0, 0, 0});
  for (const Point3 shift : {Point3{1.0, 0.5, 0.25}, Point3{1.0, 0.3, 0.7}}) {
    const std::string msg = refusal(join(one, cube(2, 1.0, shift)));
    EXPECT_THAT(msg, AllOf(HasSubstr("cubes: tet "), HasSubstr("meet away from the vertices and edge they share")))
        << msg;
    const std::vector<int> t = tets_named(msg);
    ASSERT_EQ(t.size(), 3u) << msg;  // the place, then the two triangles' tets
    EXPECT_EQ(t[0], std::min(t[1], t[2]));
    EXPECT_LE(std::min(t[1], t[2]), 48) << msg;  // one from each copy
    EXPECT_GT(std::max(t[1], t[2]), 48) << msg;
  }
}

TEST(MeshOverlap, CopiesShiftedInTheirWallPlanesAreRefused) {
  // Shifted by half a cell along x only: the walls y = 0, y = 2, z = 0, z = 2
  // of the two copies lie in one plane and overlap there (the exact in-plane
  // test), every vertex distinct.
  const TetSoup one = cube(2, 1.0, {0, 0, 0});
  const std::string msg = refusal(join(one, cube(2, 1.0, {0.5, 0, 0})));
  EXPECT_THAT(msg, HasSubstr("meet away from the vertices and edge they share")) << msg;
}

TEST(MeshOverlap, CopyNestedInsideABiggerOneIsRefused) {
  const TetSoup big = cube(4, 1.0, {0, 0, 0});  // 384 tets
  const TetSoup small = cube(1, 1.5, {1.2, 1.3, 1.1});
  const std::string msg = refusal(join(big, small));
  EXPECT_THAT(msg, AllOf(HasSubstr("cubes: tet "), HasSubstr("holds the centroid of the boundary triangle"),
                         HasSubstr("a part of the mesh lies inside another")))
      << msg;
  const std::vector<int> t = tets_named(msg);
  ASSERT_GE(t.size(), 3u) << msg;
  EXPECT_LE(t[1], 384) << msg;  // a tet of the big cube holds a centroid of the small one's boundary
  EXPECT_GT(t[2], 384) << msg;
  // The other way round in the file: the same verdict.
  EXPECT_THAT(refusal(join(small, big)), HasSubstr("a part of the mesh lies inside another"));
}

TEST(MeshOverlap, CrackThroughADuplicatedVertexIsRefused) {
  // Medit: tet K uses vertex 28, a copy of the centre vertex 14 its
  // neighbours use.
  const TetSoup one = cube(2, 1.0, {0, 0, 0});
  std::ostringstream text;
  text << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << one.points.size() + 1 << "\n";
  for (const Point3& p : one.points) text << p.x << " " << p.y << " " << p.z << " 0\n";
  text << "1 1 1 0\nTetrahedra\n" << one.tets.size() << "\n";
  int cracked = 0;
  for (std::size_t t = 0; t < one.tets.size(); ++t) {
    for (auto v : one.tets[t]) {
      const bool swap = cracked == 0 && v == 13;
      if (swap) cracked = int(t) + 1;
      text << (swap ? 28u : v + 1) << " ";
    }
    text << "1\n";
  }
  text << "End\n";
  ASSERT_GT(cracked, 0);
  const std::string msg = refusal(read_medit(text.str(), "crack.mesh"));
  EXPECT_THAT(msg, AllOf(HasSubstr("crack.mesh: vertex 14: vertices 14 and 28 are at the same position (1, 1, 1)"),
                         HasSubstr("tet " + std::to_string(cracked) + " uses vertex 28"),
                         HasSubstr("not by duplicated vertices")))
      << msg;
}

TEST(MeshOverlap, TwoTetsOverlappingAroundASharedVertexAreRefused) {
  // Tets sharing vertex 1 only, the second turned a little about it: their
  // boundary triangles at vertex 1 overlap (the shared-vertex test, off any
  // coordinate plane).
  TetSoup s;
  s.source = "fan.mesh";
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0.2, 0.1}, {-0.1, 1, 0.2}, {0.1, 0.1, 1}};
  s.tets = {{0, 1, 2, 3}, {0, 4, 5, 6}};
  s.tet_region = {1, 1};
  ASSERT_EQ(orient3d(s.points[0], s.points[4], s.points[5], s.points[6]), Sign::Positive);
  EXPECT_THAT(refusal(s), AllOf(HasSubstr("fan.mesh: tet 1: the boundary triangle"), HasSubstr("of tet 1"),
                                HasSubstr("of tet 2"), HasSubstr("meet away")));
}

TEST(MeshOverlap, CrossingFoundWhenBoxSizesDiffer) {
  // One big tet and a small fine cube across its face x + y + z = 10: the
  // boxes are too different for the grid, the candidates come from CGAL's
  // box intersection; the crossing is found all the same.
  TetSoup s;
  s.source = "mixed.mesh";
  s.points = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  s.tets = {{0, 1, 2, 3}};
  s.tet_region = {1};
  const TetSoup small = cube(3, 0.1, {3.2, 3.3, 3.35});  // spans x + y + z from 9.85 to 10.75
  const std::string msg = refusal(join(s, small));
  EXPECT_THAT(msg, HasSubstr("meet away")) << msg;
  EXPECT_THAT(tets_named(msg), Contains(1)) << msg;  // the big tet is one of the two
}

// ---- accepted

TEST(MeshOverlap, CubesTouchingAlongAnEdgeOrAtACornerAreAccepted) {
  // Cells of one lattice, so the cubes share the vertices where they touch.
  const TetSoup lattice = cube(2, 1.0, {0, 0, 0});
  const TetSoup edge = keep_tets(lattice, [](const Point3& c) { return c.z < 1 && (c.x < 1) == (c.y < 1); });
  const TetSoup corner = keep_tets(lattice, [](const Point3& c) { return (c.x < 1) == (c.y < 1) && (c.y < 1) == (c.z < 1); });
  for (const TetSoup* s : {&edge, &corner}) {
    SelfOverlapStats st;
    const ClassifiedTetMesh m = classify(*s);
    EXPECT_EQ(m.num_tets(), 12u);
    check_self_overlap(m, &st);
    EXPECT_EQ(st.pieces, 2u);  // the two cubes' boundaries: joined at a non-manifold edge or vertex only
    EXPECT_EQ(st.boundary_triangles, 24u);
  }
}

TEST(MeshOverlap, CubesTouchingFaceToFaceWithTheirOwnVerticesAreACrack) {
  // Two cubes meeting in the plane x = 2, each with its own vertices there:
  // not one mesh (the tets do not share the triangles), refused.
  const std::string msg = refusal(join(cube(2, 1.0, {0, 0, 0}), cube(2, 1.0, {2, 0, 0})));
  EXPECT_THAT(msg, AllOf(HasSubstr("vertices 3 and 28 are at the same position (2, 0, 0)"), HasSubstr("crack")));
}

TEST(MeshOverlap, APartInsideACavityIsAccepted) {
  // A shell [0,4]^3 minus (1,3)^3 with a cube [1.5,2.5]^3 in its cavity:
  // three boundary pieces, nested but covering no place twice.
  const TetSoup shell = keep_tets(cube(4, 1.0, {0, 0, 0}), [](const Point3& c) {
    return !(c.x > 1 && c.x < 3 && c.y > 1 && c.y < 3 && c.z > 1 && c.z < 3);
  });
  const TetSoup s = join(shell, cube(1, 1.0, {1.5, 1.5, 1.5}));
  SelfOverlapStats st;
  const ClassifiedTetMesh m = classify(s);
  check_self_overlap(m, &st);
  EXPECT_EQ(st.pieces, 3u);
  // A cube that reaches from the cavity into the shell: refused.
  EXPECT_THAT(refusal(join(shell, cube(1, 1.5, {1.8, 1.7, 1.9}))), HasSubstr("meet away"));
  // One that engulfs the cavity, its boundary inside the shell: refused.
  EXPECT_THAT(refusal(join(shell, cube(1, 2.25, {0.9, 0.8, 0.85}))), HasSubstr("lies inside another"));
  // And a cube in the shell's wall (no boundary crossing) is nested: refused.
  EXPECT_THAT(refusal(join(shell, cube(1, 0.5, {0.25, 0.3, 0.35}))), HasSubstr("lies inside another"));
}

TEST(MeshOverlap, UnusedCoincidentVerticesAreNotRefused) {
  // A point no tet uses may sit on a vertex (a construction point): dropped.
  TetSoup s = cube(2, 1.0, {0, 0, 0});
  s.points.push_back(s.points[13]);
  EXPECT_EQ(refusal(s), "accepted");
}

TEST(MeshOverlap, RandomMultiMaterialAndFractureMeshesAreAccepted) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    RandomMeshParams p;
    p.seed = seed;
    p.num_points = 300;
    p.regions = 1 + int(seed % 2);
    p.fracture = seed % 3 != 0;
    p.network = seed == 4;
    p.fins = seed == 5;
    p.notch = seed == 6;
    p.lattice_points = seed == 3;
    const TetSoup s = random_classified_mesh(p);
    SelfOverlapStats st;
    ClassifiedTetMesh m;
    ASSERT_NO_THROW(m = classify(s)) << "seed " << seed;
    check_self_overlap(m, &st);
    // The box's wall is one piece; the notch's jagged walls may meet the rest
    // at non-manifold edges (more pieces, then compared for nesting).
    if (!p.notch) EXPECT_EQ(st.pieces, 1u) << "seed " << seed;
    EXPECT_GT(st.tested_pairs, st.boundary_triangles) << "seed " << seed;
  }
}

TEST(MeshOverlap, BuiltInDomainsAreAccepted) {
  for (Domain d : {Domain::Cube, Domain::TwoMat, Domain::Fichera, Domain::Fracture, Domain::Network, Domain::Fins}) {
    const TetSoup s = generate_domain(d, 2000);
    ClassifiedTetMesh m;
    ASSERT_NO_THROW(m = classify(s)) << domain_name(d);
    SelfOverlapStats st;
    check_self_overlap(m, &st);
    EXPECT_EQ(st.pieces, 1u) << domain_name(d);
  }
}

TEST(MeshOverlap, FixturesAreAccepted) {
  for (const char* name : {"cube5.mesh", "cgal_twomat_patches.mesh", "cgal_twomat_sides.mesh"})
    EXPECT_EQ(refusal(read_medit_file(std::string(POLYDUAL_TEST_DATA) + "/" + name)), "accepted") << name;
}

// ---- properties on random lattice meshes

// Whether some of 4000 random points of the box [lo, hi] lies strictly
// inside two tets (EXACT: orient3d on the sample's doubles): a witness that
// the tets overlap.
bool overlap_witnessed(const TetSoup& s, Point3 lo, Point3 hi, std::mt19937& rng) {
  std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
  for (int k = 0; k < 4000; ++k) {
    const Point3 x{ux(rng), uy(rng), uz(rng)};
    int inside = 0;
    for (const auto& t : s.tets) {
      bool in = true;
      for (const auto& f : kTetFace)
        in = in && orient3d(s.points[t[f[0]]], s.points[t[f[1]]], s.points[t[f[2]]], x) == Sign::Negative;
      inside += in;
    }
    if (inside >= 2) return true;
  }
  return false;
}

TEST(MeshOverlap, RandomLatticeSubsetsAreAcceptedAndExtraPartsOnlyIfTheyOverlapNothing) {
  // Any subset of a conformal lattice's tets covers no place twice (touching
  // along non-manifold edges and at corners, with cavities): accepted, also
  // with one more of the lattice's tets. A tet on random lattice points, or a
  // small cube dropped anywhere, is refused whenever a sample point lies in
  // two tets (an accepted mesh has no such point; a refusal without one may
  // be a crack or an overlap the samples missed).
  const TetSoup lattice = cube(3, 1.0, {0, 0, 0});
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> at(0.0, 3.0), size(0.05, 1.2);
  int witnessed = 0, nested = 0, accepted = 0;
  for (int trial = 0; trial < 60; ++trial) {
    TetSoup s = lattice;
    s.tets.clear();
    s.tet_region.clear();
    std::vector<std::size_t> unused;
    for (std::size_t t = 0; t < lattice.tets.size(); ++t) {
      if (rng() % 3 != 0) {
        unused.push_back(t);
        continue;
      }
      s.tets.push_back(lattice.tets[t]);
      s.tet_region.push_back(1);
    }
    if (s.tets.empty() || unused.empty()) continue;
    ASSERT_EQ(refusal(s), "accepted") << "trial " << trial;
    TetSoup more = s;
    more.tets.push_back(lattice.tets[unused[rng() % unused.size()]]);
    more.tet_region.push_back(1);
    ASSERT_EQ(refusal(more), "accepted") << "trial " << trial;
    // A tet on four random lattice points.
    std::array<std::uint32_t, 4> extra;
    for (auto& v : extra) v = std::uint32_t(rng() % lattice.points.size());
    const Sign o = orient3d(s.points[extra[0]], s.points[extra[1]], s.points[extra[2]], s.points[extra[3]]);
    if (o != Sign::Zero) {
      if (o == Sign::Negative) std::swap(extra[0], extra[1]);
      more = s;
      more.tets.push_back(extra);
      more.tet_region.push_back(1);
      const bool overlap = overlap_witnessed(more, {0, 0, 0}, {3, 3, 3}, rng);
      witnessed += overlap;
      if (overlap) EXPECT_NE(refusal(more), "accepted") << "trial " << trial << ": an overlapping mesh was accepted";
    }
    // A cube of 6 tets of random size at a random place.
    const double h = size(rng);
    const Point3 p{at(rng), at(rng), at(rng)};
    more = join(s, cube(1, h, p));
    const bool overlap = overlap_witnessed(more, p, p + Point3{h, h, h}, rng);
    witnessed += overlap;
    const std::string msg = refusal(more);
    if (overlap) EXPECT_NE(msg, "accepted") << "trial " << trial << ": an overlapping mesh was accepted";
    nested += msg.find("lies inside another") != std::string::npos;
    accepted += msg == "accepted";
  }
  EXPECT_GT(witnessed, 20);
  EXPECT_GT(nested, 0);   // some cubes fell inside the material without crossing its walls
  EXPECT_GT(accepted, 0); // and some into the empty space
}

// ---- the command

TEST(MeshOverlap, ConvertRefusesACrackWithExitCodeOneAndWritesNothing) {
  const fs::path dir = fs::temp_directory_path() / ("polydual_overlap_" + std::to_string(getpid()));
  fs::create_directories(dir);
  // The first tet that uses the centre vertex 14 takes its copy 28.
  TetSoup one = cube(2, 1.0, {0, 0, 0});
  one.points.push_back(one.points[13]);
  for (auto& t : one.tets) {
    auto it = std::find(t.begin(), t.end(), 13u);
    if (it != t.end()) {
      *it = 27;
      break;
    }
  }
  write_medit(one, (dir / "crack.mesh").string());
  const polydual::testing::CmdResult r =
      polydual::testing::run_polydual("convert " + (dir / "crack.mesh").string() + " -o " + (dir / "out.vtu").string());
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_THAT(r.out, AllOf(HasSubstr("crack.mesh: vertex 14: vertices 14 and 28 are at the same position"),
                           HasSubstr("holds a crack")));
  EXPECT_FALSE(fs::exists(dir / "out.vtu"));
  fs::remove_all(dir);
}

// ---- the exact tests

std::vector<Point3> pts(std::initializer_list<Point3> p) { return p; }
std::array<VertexId, 3> tri(int a, int b, int c) { return {VertexId(a), VertexId(b), VertexId(c)}; }

TEST(MeshOverlap, Orient2dAndCentroidSigns) {
  EXPECT_EQ(orient2d(0, 0, 1, 0, 0, 1), Sign::Positive);  // counterclockwise
  EXPECT_EQ(orient2d(0, 0, 0, 1, 1, 0), Sign::Negative);
  // 0.1 + 0.2 != 0.3 in doubles: the exact sign of three nearly collinear points.
  EXPECT_EQ(orient2d(0, 0, 1, 1, 0.1 + 0.2, 0.3), Sign::Negative);
  EXPECT_EQ(orient2d(0, 0, 1, 1, 1e-300, 1e-300), Sign::Zero);
  const Point3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  // The centroid of (0,0,1), (0,0,-1), (3,3,0) is (1,1,0): in the plane z = 0.
  EXPECT_EQ(orient3d_centroid(a, b, c, {0, 0, 1}, {0, 0, -1}, {3, 3, 0}), Sign::Zero);
  EXPECT_EQ(orient3d_centroid(a, b, c, {0, 0, 1}, {0, 0, -1}, {3, 3, 1e-300}), Sign::Positive);
  EXPECT_EQ(orient3d_centroid(a, b, c, {0, 0, 1}, {0, 0, -1}, {3, 3, -1e-300}), Sign::Negative);
  // z = (0.1 + 0.2 + 0) / 3 is exactly the double 0.1 (0.2 is twice it), though
  // fl(0.1 + 0.2) / 3 is not: the centroid lies in the plane z = 0.1.
  EXPECT_EQ(orient3d_centroid({0, 0, 0.1}, {1, 0, 0.1}, {0, 1, 0.1}, {0, 0, 0.1}, {0, 0, 0.2}, {0, 0, 0.0}),
            Sign::Zero);
}

TEST(MeshOverlap, TrianglesCrossSharedEdge) {
  // Coplanar on the same side of the shared edge: they overlap; opposite sides: not.
  EXPECT_TRUE(triangles_cross(tri(0, 1, 2), tri(1, 0, 3), pts({{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, 2, 0}})));
  EXPECT_FALSE(triangles_cross(tri(0, 1, 2), tri(1, 0, 3), pts({{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, -2, 0}})));
  EXPECT_FALSE(triangles_cross(tri(0, 1, 2), tri(1, 0, 3), pts({{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, 2, 1e-300}})));
  // The same off the coordinate planes (CGAL's coplanar test).
  EXPECT_TRUE(triangles_cross(tri(0, 1, 2), tri(1, 0, 3), pts({{0, 0, 0}, {2, 2, 2}, {1, 2, 3}, {1, 3, 5}})));
  EXPECT_FALSE(triangles_cross(tri(0, 1, 2), tri(1, 0, 3), pts({{0, 0, 0}, {2, 2, 2}, {1, 2, 3}, {1, 0, -1}})));
}

TEST(MeshOverlap, TrianglesCrossSharedVertex) {
  const std::vector<Point3> p = pts({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 1, 0}, {-1, 1, 0}, {-2, 0, 0}, {1, 1, 1}});
  EXPECT_TRUE(triangles_cross(tri(0, 1, 2), tri(0, 3, 4), p));   // sectors overlap in z = 0
  EXPECT_FALSE(triangles_cross(tri(0, 1, 2), tri(0, 4, 5), p));  // the sector next to it: touch at 0 only
  EXPECT_FALSE(triangles_cross(tri(0, 1, 2), tri(0, 2, 4), p));  // a shared edge (0, 2), opposite sides
  EXPECT_FALSE(triangles_cross(tri(0, 1, 2), tri(0, 6, 5), p));  // out of the plane: the segment (6, 5) misses
  // Touching along a ray: the second's edge (0, 3) runs inside the first's edge (0, 1).
  EXPECT_TRUE(triangles_cross(tri(0, 1, 2), tri(0, 3, 4), pts({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0, 0}, {1, -1, 0}})));
  // Piercing: (0, 3, 4) passes through (0, 1, 2) along a segment from 0.
  EXPECT_TRUE(triangles_cross(tri(0, 1, 2), tri(0, 3, 4), pts({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 1, -1}, {0.5, 0.2, 1}})));
}

TEST(MeshOverlap, TrianglesCrossNoSharedVertex) {
  const std::vector<Point3> p = pts({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 1, 0}, {3, 1, 0}, {1, 3, 0},
                                     {1.5, 1.5, 0}, {1, 0.5, -1}, {1, 0.5, 1}, {0.2, 0.2, 1}});
  EXPECT_TRUE(triangles_cross(tri(0, 1, 2), tri(3, 4, 5), p));   // coplanar, overlapping
  EXPECT_FALSE(triangles_cross(tri(0, 1, 2), tri(6, 4, 5), p));  // coplanar, apart: (1.5, 1.5) beyond x + y = 2
  EXPECT_TRUE(triangles_cross(tri(0, 1, 2), tri(7, 8, 9), p));   // piercing
}

}  // namespace
}  // namespace polydual
