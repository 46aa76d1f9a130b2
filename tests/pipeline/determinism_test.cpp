// The whole pipeline gives the same result for any thread count: classify ->
// build_dual -> star_shaped_verdicts -> optimize (local and global) ->
// star_shaped_verdicts -> VTU, run with 1, 2 and 4 TBB threads (4 oversubscribes
// a 2-core machine, which is the point: more interleavings), comparing every
// array of the PolyMesh (points bit for bit), every verdict, the optimiser's
// records and the bytes of the VTU file.
#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

#include "classify/classify.h"
#include "dual/build_dual.h"
#include "generate/domains.h"
#include "generate/random_mesh.h"
#include "io/vtu_poly_writer.h"
#include "optim/optimize.h"
#include "pipeline/convert.h"
#include "quality/star_verdict.h"

using namespace polydual;

namespace {

struct StageParams {
  ClassifyParams classify;
  DualParams dual;
  OptimParams optim;
};

struct StageResult {
  PolyMesh mesh;
  std::vector<CellVerdict> verdicts_before, verdicts_after;
  OptimReport optim;
  std::string vtu_ascii, vtu_binary;  // the written files' bytes
};

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}


// The stages composed as the convert command composes them. It stands for the
// library's polydual::convert() entry (being written): when that lands, this
// helper becomes a call to it and the comparisons below stay as they are.
StageResult run_stages(const TetSoup& soup, const StageParams& p, const std::string& tag) {
  StageResult r;
  const ClassifiedTetMesh m = classify(soup, p.classify);
  r.mesh = build_dual(m, p.dual);
  r.verdicts_before = star_shaped_verdicts(r.mesh);
  const ModelFacets facets = model_facets(m);
  r.optim = optimize(r.mesh, &facets, p.optim);
  r.verdicts_after = star_shaped_verdicts(r.mesh);
  // The library entry runs the same stages: the same mesh and verdicts.
  PipelineParams pp;
  pp.classify = p.classify;
  pp.dual = p.dual;
  pp.optim = p.optim;
  pp.split.enabled = false;  // the stages above build no cuts
  pp.tetopt.enabled = false;  // nor move the tets
  const ConvertResult c = convert(soup, pp);
  EXPECT_TRUE(c.mesh.points == r.mesh.points) << tag;
  EXPECT_TRUE(c.mesh.face_points == r.mesh.face_points) << tag;
  EXPECT_EQ(c.mesh.cell_offsets, r.mesh.cell_offsets) << tag;
  EXPECT_EQ(c.check.verdicts.size(), r.verdicts_after.size()) << tag;
  for (std::size_t i = 0; i < c.check.verdicts.size() && i < r.verdicts_after.size(); ++i)
    EXPECT_EQ(c.check.verdicts[i].bad_tets, r.verdicts_after[i].bad_tets) << tag << " cell " << i;
  const std::string base = (std::filesystem::temp_directory_path() /
                            ("polydual_determinism_" + std::to_string(getpid()) + "_" + tag)).string();
  write_vtu_poly(r.mesh, base + "_a.vtu", verdict_fields(r.verdicts_after), {});
  VtuOptions bin;
  bin.binary = true;
  write_vtu_poly(r.mesh, base + "_b.vtu", verdict_fields(r.verdicts_after), bin);
  r.vtu_ascii = file_bytes(base + "_a.vtu");
  r.vtu_binary = file_bytes(base + "_b.vtu");
  std::filesystem::remove(base + "_a.vtu");
  std::filesystem::remove(base + "_b.vtu");
  return r;
}

// run_stages with at most n TBB threads, in an arena of n threads (more than
// the machine's cores when n is larger: global_control alone only lowers).
StageResult run_with_threads(int n, const TetSoup& soup, const StageParams& p, const std::string& tag) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(n));
  tbb::task_arena arena(n);
  StageResult r;
  arena.execute([&] {
    EXPECT_EQ(tbb::this_task_arena::max_concurrency(), n);
    r = run_stages(soup, p, tag + "_t" + std::to_string(n));
  });
  return r;
}

std::vector<std::uint64_t> bits(const std::vector<Point3>& pts) {
  std::vector<std::uint64_t> b;
  for (const Point3& p : pts)
    for (double x : {p.x, p.y, p.z}) b.push_back(std::bit_cast<std::uint64_t>(x));
  return b;
}

void expect_same_verdicts(const std::vector<CellVerdict>& a, const std::vector<CellVerdict>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t c = 0; c < a.size(); ++c) {
    ASSERT_EQ(a[c].valid, b[c].valid) << what << " cell " << c;
    ASSERT_EQ(a[c].bad_tets, b[c].bad_tets) << what << " cell " << c;
    ASSERT_EQ(a[c].total_tets, b[c].total_tets) << what << " cell " << c;
  }
}

void expect_same(const StageResult& a, const StageResult& b) {
  const PolyMesh &x = a.mesh, &y = b.mesh;
  EXPECT_EQ(bits(x.points), bits(y.points));
  EXPECT_TRUE(x.point_class == y.point_class);
  EXPECT_EQ(x.face_offsets, y.face_offsets);
  EXPECT_TRUE(x.face_points == y.face_points);
  EXPECT_TRUE(x.face_owner == y.face_owner);
  EXPECT_TRUE(x.face_neighbour == y.face_neighbour);
  EXPECT_TRUE(x.face_kind == y.face_kind);
  EXPECT_EQ(x.face_tag, y.face_tag);
  EXPECT_EQ(x.cell_offsets, y.cell_offsets);
  EXPECT_TRUE(x.cell_faces == y.cell_faces);
  EXPECT_EQ(x.cell_material, y.cell_material);
  EXPECT_TRUE(x.cell_primal == y.cell_primal);
  expect_same_verdicts(a.verdicts_before, b.verdicts_before, "before");
  expect_same_verdicts(a.verdicts_after, b.verdicts_after, "after");
  EXPECT_EQ(a.optim.invalid_before, b.optim.invalid_before);
  EXPECT_EQ(a.optim.invalid_after, b.optim.invalid_after);
  EXPECT_EQ(a.optim.vertex_updates, b.optim.vertex_updates);
  ASSERT_EQ(a.optim.iterations.size(), b.optim.iterations.size());
  for (std::size_t i = 0; i < a.optim.iterations.size(); ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.optim.iterations[i].objective),
              std::bit_cast<std::uint64_t>(b.optim.iterations[i].objective)) << "iteration " << i;
    EXPECT_EQ(a.optim.iterations[i].invalid, b.optim.iterations[i].invalid) << "iteration " << i;
    EXPECT_EQ(a.optim.iterations[i].visited, b.optim.iterations[i].visited) << "iteration " << i;
    EXPECT_EQ(a.optim.iterations[i].updates, b.optim.iterations[i].updates) << "iteration " << i;
  }
  EXPECT_TRUE(a.vtu_ascii == b.vtu_ascii) << "ASCII VTU bytes differ";
  EXPECT_TRUE(a.vtu_binary == b.vtu_binary) << "binary VTU bytes differ";
}

void check_thread_counts(const TetSoup& soup, const std::string& name) {
  for (auto method : {OptimParams::Method::Local, OptimParams::Method::Global}) {
    SCOPED_TRACE(name + (method == OptimParams::Method::Local ? " local" : " global"));
    StageParams p;
    p.optim.method = method;
    p.optim.max_iter = 2;
    p.optim.global_iterations_per_round = 20;
    const StageResult one = run_with_threads(1, soup, p, name);
    // The case must exercise the optimiser: invalid cells to untangle, moves made.
    EXPECT_GT(one.optim.invalid_before, 0);
    EXPECT_GT(one.optim.vertex_updates, 0u);
    EXPECT_FALSE(one.vtu_ascii.empty());
    for (int n : {2, 4}) {
      SCOPED_TRACE("threads " + std::to_string(n));
      expect_same(one, run_with_threads(n, soup, p, name));
    }
  }
}

}  // namespace

TEST(Determinism, RandomMeshWithFractureAnyThreadCount) {
  RandomMeshParams params;
  params.seed = 11;
  params.num_points = 500;
  params.regions = 2;
  params.fracture = true;
  check_thread_counts(random_classified_mesh(params), "random");
}

TEST(Determinism, DomainMeshAnyThreadCount) {
  check_thread_counts(generate_domain(Domain::Fracture, 2500), "fracture_domain");
}
