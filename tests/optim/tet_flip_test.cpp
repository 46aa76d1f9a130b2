// The Delaunay flip pass after the tet optimiser (optim/tet_flip.h,
// proofs/tet_optimize.md F1-F4): positive tets, the classified structure kept
// exactly, exact volumes per material kept, the free non-Delaunay faces
// repaired, a Delaunay input left alone, the same result for any thread count.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <tuple>

#include "classify/classify.h"
#include "core/error.h"
#include "classified_structure.h"
#include "exact_volume.h"
#include "generate/random_mesh.h"
#include "optim/tet_flip.h"
#include "optim/tet_optimize.h"
#include "predicates/predicates.h"
#include "run_command.h"

namespace polydual {
namespace {

ClassifiedTetMesh random_mesh(std::uint64_t seed, int regions, bool fracture, int n, bool network = false,
                              bool notch = false, bool lattice = false) {
  RandomMeshParams p;
  p.seed = seed;
  p.num_points = n;
  p.regions = regions;
  p.fracture = fracture;
  p.network = network;
  p.notch = notch;
  p.lattice_points = lattice;
  return classify(random_classified_mesh(p));
}

// The tet optimiser's moves alone (no flips): the input the flip pass repairs.
ClassifiedTetMesh moved(ClassifiedTetMesh m) {
  TetOptParams p;
  p.enabled = true;
  p.flips.enabled = false;
  return optimize_tets(m, p);
}

std::size_t non_positive_tets(const ClassifiedTetMesh& m) {
  std::size_t bad = 0;
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const auto& v = m.tet(TetId(t));
    bad += orient3d(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3])) != Sign::Positive;
  }
  return bad;
}

using testing::constrained_edges;
using testing::EdgeKey;
using testing::model_face_triangles;
using testing::TriKey;

TetSoup soup_of(const ClassifiedTetMesh& m) {
  TetSoup soup;
  soup.points = m.points();
  for (std::size_t t = 0; t < m.num_tets(); ++t) {
    const auto& v = m.tet(TetId(t));
    soup.tets.push_back({v[0].idx, v[1].idx, v[2].idx, v[3].idx});
    soup.tet_region.push_back(m.region(TetId(t)));
  }
  for (const TriKey& k : model_face_triangles(m))
    soup.triangles.push_back({{std::get<0>(k), std::get<1>(k), std::get<2>(k)}, std::get<3>(k)});
  return soup;
}

// Everything the flips must keep, checked between the moved mesh and the result.
void expect_structure_kept(const ClassifiedTetMesh& before, const ClassifiedTetMesh& after) {
  EXPECT_EQ(non_positive_tets(after), 0u);
  ASSERT_EQ(after.num_vertices(), before.num_vertices());
  EXPECT_EQ(after.points(), before.points());
  for (std::size_t v = 0; v < after.num_vertices(); ++v)
    ASSERT_EQ(after.vertex_class(VertexId(v)), before.vertex_class(VertexId(v))) << "vertex " << v;
  EXPECT_EQ(model_face_triangles(after), model_face_triangles(before));
  EXPECT_EQ(constrained_edges(after), constrained_edges(before));
  // Every other edge lies inside the region of its tets, as classify() says.
  for (std::size_t e = 0; e < after.num_edges(); ++e) {
    const ModelRef r = after.edge_class(EdgeId(e));
    if (r.dim < 3) continue;
    bool closed = false;
    const std::vector<TetId> ring = after.edge_ring(EdgeId(e), &closed);
    EXPECT_TRUE(closed) << "edge " << e << " classified in a region is on the boundary";
    for (TetId t : ring) ASSERT_EQ(after.region(t), r.tag) << "edge " << e;
  }
  EXPECT_EQ(testing::exact_primal_volumes(after), testing::exact_primal_volumes(before));
  EXPECT_EQ(after.model().count(2), before.model().count(2));
  // classify() of the two meshes' soups (tets, regions, model-face triangles
  // with their tags) finds the same model: the flips made no triangle or
  // edge that classify() would put on the model.
  const ClassifiedTetMesh a = classify(soup_of(before)), b = classify(soup_of(after));
  for (int d = 0; d <= 3; ++d) EXPECT_EQ(b.model().count(d), a.model().count(d)) << "dimension " << d;
  EXPECT_EQ(model_face_triangles(b), model_face_triangles(a));
  EXPECT_EQ(constrained_edges(b), constrained_edges(a));
}

TEST(TetFlip, RepairsTheDelaunayPropertyTheMovesBroke) {
  const ClassifiedTetMesh m = moved(random_mesh(11, 1, false, 400));
  TetFlipReport rep;
  const ClassifiedTetMesh f = delaunay_flips(m, {}, &rep);
  std::printf("free non-Delaunay faces %zu -> %zu; flips 2-3 %llu, 3-2 %llu; blocked %llu/%llu/%llu\n",
              rep.before.free, rep.after.free, (unsigned long long)rep.flips23, (unsigned long long)rep.flips32,
              (unsigned long long)rep.blocked_nonconvex, (unsigned long long)rep.blocked_degenerate,
              (unsigned long long)rep.blocked_constrained_edge);
  EXPECT_GT(rep.before.free, 100u);
  EXPECT_GT(rep.flips23, 0u);
  EXPECT_GT(rep.flips32, 0u);
  EXPECT_LE(rep.after.free, rep.before.free / 50);  // near zero: only blocked configurations stay
  EXPECT_EQ(rep.after.free, count_non_delaunay(f).free);
  EXPECT_EQ(rep.tets_after, f.num_tets());
  EXPECT_EQ(f.num_tets(), m.num_tets() + rep.flips23 - rep.flips32);
  EXPECT_FALSE(rep.hit_limit);
  expect_structure_kept(m, f);
}

TEST(TetFlip, KeepsTheClassifiedStructureOnMaterialsAndFractures) {
  struct Case {
    std::uint64_t seed;
    int regions;
    bool fracture, network, notch;
  };
  for (const Case& c : {Case{3, 2, true, false, false}, Case{5, 2, true, true, false}, Case{6, 1, true, false, true}}) {
    SCOPED_TRACE(c.seed);
    const ClassifiedTetMesh m = moved(random_mesh(c.seed, c.regions, c.fracture, 500, c.network, c.notch));
    TetFlipReport rep;
    const ClassifiedTetMesh f = delaunay_flips(m, {}, &rep);
    EXPECT_GT(rep.flips23 + rep.flips32, 50u);
    EXPECT_LT(rep.after.free, rep.before.free / 10);
    expect_structure_kept(m, f);
  }
}

// Model edges inside a region (file-tagged curves: no model face around them)
// are guarded only by their edge classification: all three faces around such
// an edge may be free.
TEST(TetFlip, NeverRemovesAModelEdgeInsideARegion) {
  RandomMeshParams p;
  p.seed = 13;
  p.num_points = 500;
  TetSoup soup = random_classified_mesh(p);
  std::int32_t tag = 700;
  for (std::size_t t = 0; t < soup.tets.size(); t += 7) {  // every edge of every 7th tet
    const auto& v = soup.tets[t];
    for (int k = 0; k < 6; ++k) soup.edges.push_back({{v[kTetEdge[k][0]], v[kTetEdge[k][1]]}, tag});
    ++tag;
  }
  const ClassifiedTetMesh m = moved(classify(soup));
  const std::size_t inner = [&] {
    std::size_t n = 0;
    for (std::size_t e = 0; e < m.num_edges(); ++e) n += m.edge_class(EdgeId(e)).dim == 1;
    return n;
  }();
  ASSERT_GT(inner, 500u);
  TetFlipReport rep;
  const ClassifiedTetMesh f = delaunay_flips(m, {}, &rep);
  EXPECT_GT(rep.blocked_constrained_edge, 0u);
  expect_structure_kept(m, f);
}

// Strongly perturbed Kuhn lattices (cospherical before the perturbation, many
// non-convex pairs after): every flip's new tets must be checked positive.
TEST(TetFlip, PerturbedLatticesStayValid) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE(seed);
    TetSoup s = kuhn_lattice(6, 6, 6, 1, 1, 1, 2);
    std::uint64_t x = seed * 0x9E3779B97F4A7C15ull;
    for (Point3& q : s.points)
      for (int k = 0; k < 3; ++k) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;  // xorshift: portable
        const double r = (double(x >> 11) / double(1ull << 53) - 0.5) * 0.5;
        if (q[k] != 0 && q[k] != 6) q[k] += r;
      }
    ClassifiedTetMesh m;
    try {
      m = classify(s);
    } catch (const InputError&) {
      continue;  // the perturbation inverted a tet: not an input
    }
    TetFlipReport rep;
    const ClassifiedTetMesh f = delaunay_flips(m, {}, &rep);
    std::printf("seed %llu: flips %llu, blocked non-convex %llu\n", (unsigned long long)seed,
                (unsigned long long)(rep.flips23 + rep.flips32), (unsigned long long)rep.blocked_nonconvex);
    EXPECT_GT(rep.flips23 + rep.flips32, 100u);
    expect_structure_kept(m, f);
  }
}

TEST(TetFlip, DegenerateLatticePointsStayPositive) {
  // Many cospherical and coplanar points: insphere Zero never flips, orient3d
  // Zero never creates a flat tet.
  const ClassifiedTetMesh m = moved(random_mesh(9, 2, true, 300, false, false, true));
  TetFlipReport rep;
  const ClassifiedTetMesh f = delaunay_flips(m, {}, &rep);
  EXPECT_GT(rep.flips23 + rep.flips32, 0u);
  expect_structure_kept(m, f);
}

TEST(TetFlip, ADelaunayMeshIsAFixedPoint) {
  const ClassifiedTetMesh m = random_mesh(12, 2, true, 400);
  TetFlipReport rep;
  const ClassifiedTetMesh f = delaunay_flips(m, {}, &rep);
  EXPECT_EQ(rep.before.free, 0u);  // CGAL's Delaunay tetrahedralisation
  EXPECT_EQ(rep.flips23 + rep.flips32, 0u);
  ASSERT_EQ(f.num_tets(), m.num_tets());
  for (std::size_t t = 0; t < m.num_tets(); ++t) EXPECT_EQ(f.tet(TetId(t)), m.tet(TetId(t)));
}

TEST(TetFlip, TheFlipBoundStopsThePass) {
  const ClassifiedTetMesh m = moved(random_mesh(11, 1, false, 400));
  TetFlipParams p;
  p.max_flips_per_tet = 0;
  TetFlipReport rep;
  const ClassifiedTetMesh f = delaunay_flips(m, p, &rep);
  EXPECT_TRUE(rep.hit_limit);
  EXPECT_EQ(rep.flips23 + rep.flips32, 0u);
  EXPECT_EQ(rep.after.free, rep.before.free);
  p.max_flips_per_tet = -1;
  EXPECT_THROW(p.validate(), UsageError);
}

TEST(TetFlip, OptimizeTetsRunsTheFlipsAndReportsThem) {
  ClassifiedTetMesh m = random_mesh(7, 2, true, 500);
  const ClassifiedTetMesh input = m;
  TetOptParams p;
  p.enabled = true;
  TetOptReport rep;
  m = optimize_tets(m, p, &rep);
  ASSERT_TRUE(rep.flipped);
  EXPECT_GT(rep.flips.flips23, 0u);
  EXPECT_EQ(rep.flips.after.free, count_non_delaunay(m).free);
  EXPECT_EQ(rep.after.mean, tet_quality_stats(m, m.points()).mean);
  EXPECT_LT(rep.after.mean, rep.before.mean);
  const Json j = rep.to_json();
  EXPECT_NE(j.dump().find("\"flips23\""), std::string::npos);
  EXPECT_EQ(model_face_triangles(m).size(), model_face_triangles(input).size());
  // The moves reshape the jagged interface, not the box: the total volume is kept.
  auto total = [](const ClassifiedTetMesh& x) {
    testing::Q sum(0);
    for (const auto& [region, v] : testing::exact_primal_volumes(x)) sum += v;
    return sum;
  };
  EXPECT_EQ(total(m), total(input));
  for (std::size_t v = 0; v < m.num_vertices(); ++v) EXPECT_EQ(m.vertex_class(VertexId(v)), input.vertex_class(VertexId(v)));
}

TEST(TetFlip, RoundsAlternateMovesAndFlips) {
  ClassifiedTetMesh one = random_mesh(7, 2, true, 500), three = one;
  const ClassifiedTetMesh input = one;
  TetOptParams p;
  p.enabled = true;
  TetOptReport r1, r3;
  one = optimize_tets(one, p, &r1);
  p.flips.rounds = 3;
  three = optimize_tets(three, p, &r3);
  EXPECT_EQ(r1.rounds, 1);
  EXPECT_EQ(r3.rounds, 3);
  EXPECT_GT(r3.flips.flips23 + r3.flips.flips32, r1.flips.flips23 + r1.flips.flips32);
  EXPECT_GT(r3.sweeps, r1.sweeps);
  EXPECT_LT(r3.after.mean, r1.after.mean);  // the later moves improve what the flips made
  EXPECT_EQ(r3.flips.after.free, count_non_delaunay(three).free);
  EXPECT_EQ(non_positive_tets(three), 0u);
  EXPECT_EQ(model_face_triangles(three).size(), model_face_triangles(input).size());
  p.flips.rounds = 0;
  EXPECT_THROW(p.validate(), UsageError);
}

TEST(TetFlip, IdenticalForOneAndTwoThreads) {
  const ClassifiedTetMesh input = random_mesh(8, 2, true, 400);
  auto run = [&](int threads) {
    tbb::global_control g(tbb::global_control::max_allowed_parallelism, threads);
    ClassifiedTetMesh m = input;
    TetOptParams p;
    p.enabled = true;
    return optimize_tets(m, p);
  };
  const ClassifiedTetMesh a = run(1), b = run(2);
  ASSERT_EQ(a.num_tets(), b.num_tets());
  for (std::size_t t = 0; t < a.num_tets(); ++t) EXPECT_EQ(a.tet(TetId(t)), b.tet(TetId(t)));
  EXPECT_EQ(a.points(), b.points());
}

// The command: --optimize-tets flips by default and reports it in the
// optimize_tets stage's JSON; --tet-flips off does not flip; bad values are
// usage errors (exit 2) naming the option.
TEST(TetFlip, CommandLineOptions) {
  namespace fs = std::filesystem;
  const fs::path d = fs::temp_directory_path() / ("polydual_tet_flip_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  const std::string msh = (d / "t.msh").string(), vtu = (d / "t.vtu").string();
  ASSERT_EQ(testing::run_polydual("generate twomat --tets 2000 -o " + msh).code, 0);
  const std::string base = "convert " + msh + " -o " + vtu + " --force --json --optimize none --optimize-tets";
  const testing::CmdResult on = testing::run_polydual(base);
  ASSERT_EQ(on.code, 0) << on.out;
  EXPECT_NE(on.out.find("\"flips23\""), std::string::npos);
  EXPECT_NE(on.out.find("\"non_delaunay_after\""), std::string::npos);
  const testing::CmdResult off = testing::run_polydual(base + " --tet-flips off");
  ASSERT_EQ(off.code, 0) << off.out;
  EXPECT_EQ(off.out.find("\"flips23\""), std::string::npos);
  const testing::CmdResult bad = testing::run_polydual(base + " --tet-flips maybe");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.out.find("--tet-flips"), std::string::npos) << bad.out;
  const testing::CmdResult rounds = testing::run_polydual(base + " --tet-flip-rounds 0");
  EXPECT_EQ(rounds.code, 2);
  EXPECT_NE(rounds.out.find("--tet-flip-rounds"), std::string::npos) << rounds.out;
  fs::remove_all(d);
}

}  // namespace
}  // namespace polydual
