// Interior points for meshes whose tets span the solid (optim/steiner.h,
// proofs/tet_optimize.md T6): inserted where a ball has vertices only on its
// surface, never into a regular mesh, the classified structure and every
// material's exact volume kept, and the dual of such a ball valid without a
// split.
#include <gtest/gtest.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <map>
#include <filesystem>
#include <set>
#include <string>
#include <tuple>

#include "classify/classify.h"
#include "core/error.h"
#include "classified_structure.h"
#include "exact_volume.h"
#include "generate/random_mesh.h"
#include "optim/steiner.h"
#include "optim/tet_optimize.h"
#include "pipeline/convert.h"
#include "predicates/predicates.h"
#include "run_command.h"

namespace polydual {
namespace {

// The Delaunay tetrahedralisation (CGAL) of n points spread evenly on the
// unit sphere (a Fibonacci lattice) and none inside, as TetGen's -pY meshes
// a thick solid from its surface points: every tet reaches across the ball.
TetSoup sphere_surface_mesh(int n) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Point_3> pts;
  TetSoup soup;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
    pts.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    soup.points.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  CGAL::Delaunay_triangulation_3<K> dt;
  std::map<CGAL::Delaunay_triangulation_3<K>::Vertex_handle, std::uint32_t> id;
  for (int i = 0; i < n; ++i) id[dt.insert(pts[i])] = std::uint32_t(i);
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    std::array<std::uint32_t, 4> t{id[c->vertex(0)], id[c->vertex(1)], id[c->vertex(2)], id[c->vertex(3)]};
    if (CGAL::orientation(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]]) == CGAL::NEGATIVE) std::swap(t[0], t[1]);
    soup.tets.push_back(t);
    soup.tet_region.push_back(1);
  }
  return soup;
}

// The unit box's Delaunay tetrahedralisation with `per_face` random points on
// each face and none inside (random_mesh.h), with the families' materials,
// sheets and notch.
ClassifiedTetMesh face_points_box(std::uint64_t seed, int per_face, int regions, bool fracture, bool network,
                                  bool notch) {
  RandomMeshParams p;
  p.seed = seed;
  p.num_points = 0;
  p.face_points = per_face;
  p.regions = regions;
  p.fracture = fracture;
  p.network = network;
  p.notch = notch;
  return classify(random_classified_mesh(p));
}

std::size_t interior_vertices(const ClassifiedTetMesh& m) {
  std::size_t n = 0;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) n += m.vertex_class(VertexId(v)).dim == 3;
  return n;
}

using testing::constrained_edges;
using testing::EdgeKey;
using testing::model_face_triangles;
using testing::TriKey;

// What an insertion must keep (T6), between the mesh given and the result:
// its vertices (first, unmoved, same class), every model-face triangle with
// its tag, every edge on a model edge or face, each region's exact volume,
// positive tets, and the new vertices inside their region.
void expect_structure_kept(const ClassifiedTetMesh& before, const ClassifiedTetMesh& after) {
  ASSERT_GE(after.num_vertices(), before.num_vertices());
  for (std::size_t v = 0; v < before.num_vertices(); ++v) {
    ASSERT_EQ(after.point(VertexId(v)), before.point(VertexId(v))) << "vertex " << v;
    ASSERT_EQ(after.vertex_class(VertexId(v)), before.vertex_class(VertexId(v))) << "vertex " << v;
  }
  for (std::size_t v = before.num_vertices(); v < after.num_vertices(); ++v) {
    EXPECT_EQ(after.vertex_class(VertexId(v)).dim, 3) << "inserted vertex " << v;
    EXPECT_GT(after.input_vertex(VertexId(v)), after.input_vertex(VertexId(v - 1)));
  }
  for (std::size_t t = 0; t < after.num_tets(); ++t) {
    const auto& v = after.tet(TetId(t));
    ASSERT_EQ(orient3d(after.point(v[0]), after.point(v[1]), after.point(v[2]), after.point(v[3])), Sign::Positive);
  }
  EXPECT_EQ(model_face_triangles(after), model_face_triangles(before));
  EXPECT_EQ(constrained_edges(after), constrained_edges(before));
  EXPECT_EQ(testing::exact_primal_volumes(after), testing::exact_primal_volumes(before));
  for (int d = 0; d <= 3; ++d) EXPECT_EQ(after.model().count(d), before.model().count(d));
}

TEST(Steiner, ABallWithVerticesOnlyOnItsSurfaceGetsInteriorOnes) {
  const ClassifiedTetMesh m = classify(sphere_surface_mesh(500));
  ASSERT_EQ(interior_vertices(m), 0u);
  SteinerReport rep;
  const ClassifiedTetMesh s = insert_interior_points(m, {}, &rep);
  std::printf("ball %zu vertices, %zu tets: inserted %zu of %zu candidates in %d passes, skipped %zu/%zu/%zu\n",
              m.num_vertices(), m.num_tets(), rep.inserted, rep.candidates, rep.passes, rep.skipped_visibility,
              rep.skipped_topology, rep.skipped_quality);
  EXPECT_EQ(rep.interior_vertices_before, 0u);
  EXPECT_GT(rep.inserted, 5u);
  EXPECT_LT(rep.inserted, m.num_vertices() / 5);  // a few points break the spanning tets
  EXPECT_EQ(s.num_vertices(), m.num_vertices() + rep.inserted);
  EXPECT_EQ(interior_vertices(s), rep.inserted);
  EXPECT_TRUE(rep.failed.empty()) << rep.failed;
  expect_structure_kept(m, s);
}

// At the lowest ratio many tets qualify: the mechanics (cavities, shrinking,
// the guards) on boxes with vertices on their faces only, with materials,
// fracture sheets, a notch and model edges inside a region.
TEST(Steiner, KeepsTheClassifiedStructureWhereverItInserts) {
  struct Case {
    std::uint64_t seed;
    int regions;
    bool fracture, network, notch, inner_edges;
  };
  for (const Case& c : {Case{3, 2, true, false, false, false}, Case{5, 2, true, true, false, false},
                        Case{6, 1, true, false, true, false}, Case{13, 1, false, false, false, true}}) {
    SCOPED_TRACE(c.seed);
    ClassifiedTetMesh m = face_points_box(c.seed, 40, c.regions, c.fracture, c.network, c.notch);
    if (c.inner_edges) {  // every edge of every 9th tet a model edge of its own
      RandomMeshParams p;
      p.seed = c.seed;
      p.num_points = 0;
      p.face_points = 40;
      TetSoup soup = random_classified_mesh(p);
      for (std::size_t t = 0; t < soup.tets.size(); t += 9)
        for (int k = 0; k < 6; ++k)
          soup.edges.push_back({{soup.tets[t][kTetEdge[k][0]], soup.tets[t][kTetEdge[k][1]]}, std::int32_t(700 + t)});
      m = classify(soup);
    }
    SteinerParams sp;
    sp.ratio = SteinerParams::kMinRatio;
    SteinerReport rep;
    const ClassifiedTetMesh s = insert_interior_points(m, sp, &rep);
    std::printf("inserted %zu of %zu candidates, skipped %zu/%zu/%zu\n", rep.inserted, rep.candidates,
                rep.skipped_visibility, rep.skipped_topology, rep.skipped_quality);
    EXPECT_GT(rep.inserted, c.inner_edges ? 0u : 50u);
    if (c.inner_edges) EXPECT_GT(rep.skipped_topology, 0u);
    expect_structure_kept(m, s);
  }
}

TEST(Steiner, ARegularMeshIsLeftAlone) {
  const ClassifiedTetMesh m = classify(kuhn_lattice(4, 4, 3, 1, 1, 1, 2));
  SteinerReport rep;
  const ClassifiedTetMesh s = insert_interior_points(m, {}, &rep);
  EXPECT_EQ(rep.candidates, 0u);
  EXPECT_EQ(rep.inserted, 0u);
  ASSERT_EQ(s.num_tets(), m.num_tets());
  for (std::size_t t = 0; t < m.num_tets(); ++t) EXPECT_EQ(s.tet(TetId(t)), m.tet(TetId(t)));
}

TEST(Steiner, TheLimitStopsIt) {
  const ClassifiedTetMesh m = classify(sphere_surface_mesh(500));
  SteinerParams p;
  p.max_points_per_vertex = 0.01;
  SteinerReport rep;
  const ClassifiedTetMesh s = insert_interior_points(m, p, &rep);
  EXPECT_TRUE(rep.hit_limit);
  EXPECT_EQ(rep.inserted, 5u);
  expect_structure_kept(m, s);
  p.ratio = 0.5;
  EXPECT_THROW(p.validate(), UsageError);
}

// The whole pipeline on the ball: without the points the optimiser leaves
// cells tangled and the split cuts vertices whole (most of them); with them
// (the default) the dual is valid as optimised, with no cell split.
TEST(Steiner, TheBallsDualNeedsNoSplitWithThem) {
  const TetSoup soup = sphere_surface_mesh(200);
  PipelineParams with, without;
  without.tetopt.steiner.enabled = false;
  const ConvertResult a = convert(soup, with), b = convert(soup, without);
  auto whole = [](const ConvertResult& r) {
    return std::stod(r.report.stage("split")->stats.find("vertices_whole")->dump());
  };
  std::printf("with points: %zu cells, %g vertices cut whole; without: %zu cells, %g cut whole\n",
              a.mesh.num_cells(), whole(a), b.mesh.num_cells(), whole(b));
  EXPECT_EQ(a.check.invalid_cells, 0u);
  EXPECT_EQ(b.check.invalid_cells, 0u);
  EXPECT_EQ(whole(a), 0);
  EXPECT_GT(whole(b), 50);
  EXPECT_EQ(a.mesh.num_cells(), a.primal.num_vertices());
  EXPECT_GT(b.mesh.num_cells(), 3 * a.mesh.num_cells());
  EXPECT_TRUE(std::any_of(a.warnings.begin(), a.warnings.end(),
                          [](const std::string& w) { return w.find("interior vertices") != std::string::npos; }));
  EXPECT_FALSE(std::any_of(b.warnings.begin(), b.warnings.end(),
                           [](const std::string& w) { return w.find("interior vertices") != std::string::npos; }));
}

// A dual with inserted points names vertices past its file's: `optimize
// --primal FILE` inserts the same ones (deterministic) and accepts it.
TEST(Steiner, OptimizeTakesTheFileTheDualWasMadeFrom) {
  namespace fs = std::filesystem;
  const fs::path d = fs::temp_directory_path() / ("polydual_steiner_primal_" + std::to_string(::getpid()));
  fs::create_directories(d);
  const std::string mesh = (d / "ball.mesh").string(), vtu = (d / "ball.vtu").string(),
                    out = (d / "again.vtu").string();
  {
    const TetSoup soup = sphere_surface_mesh(200);
    std::FILE* f = std::fopen(mesh.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "MeshVersionFormatted 2\nDimension 3\nVertices\n%zu\n", soup.points.size());
    for (const Point3& p : soup.points) std::fprintf(f, "%.17g %.17g %.17g 0\n", p.x, p.y, p.z);
    std::fprintf(f, "Tetrahedra\n%zu\n", soup.tets.size());
    for (const auto& t : soup.tets) std::fprintf(f, "%u %u %u %u 1\n", t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
    std::fprintf(f, "End\n");
    std::fclose(f);
  }
  const testing::CmdResult made = testing::run_polydual("convert " + mesh + " -o " + vtu + " --json");
  ASSERT_EQ(made.code, 0) << made.out;
  EXPECT_NE(made.out.find("inserted"), std::string::npos);
  const testing::CmdResult again = testing::run_polydual("optimize " + vtu + " -o " + out + " --primal " + mesh);
  EXPECT_EQ(again.code, 0) << again.out;
  // Without an optimiser convert inserts more points (ratio_without_optimiser).
  const testing::CmdResult raw = testing::run_polydual("convert " + mesh + " -o " + vtu + " --force --optimize none");
  ASSERT_EQ(raw.code, 0) << raw.out;
  fs::remove(out);
  const testing::CmdResult raw_again = testing::run_polydual("optimize " + vtu + " -o " + out + " --primal " + mesh);
  EXPECT_EQ(raw_again.code, 0) << raw_again.out;
  fs::remove_all(d);
}

TEST(Steiner, CommandLineOption) {
  namespace fs = std::filesystem;
  const fs::path d = fs::temp_directory_path() / ("polydual_steiner_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  const std::string msh = (d / "t.msh").string(), vtu = (d / "t.vtu").string();
  ASSERT_EQ(testing::run_polydual("generate twomat --tets 2000 -o " + msh).code, 0);
  const std::string base = "convert " + msh + " -o " + vtu + " --force --json --optimize none";
  const testing::CmdResult on = testing::run_polydual(base);
  ASSERT_EQ(on.code, 0) << on.out;
  EXPECT_NE(on.out.find("\"interior_points\""), std::string::npos);
  const testing::CmdResult off = testing::run_polydual(base + " --interior-points off");
  ASSERT_EQ(off.code, 0) << off.out;
  const testing::CmdResult bad = testing::run_polydual(base + " --interior-points maybe");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.out.find("--interior-points"), std::string::npos);
  fs::remove_all(d);
}

}  // namespace
}  // namespace polydual
