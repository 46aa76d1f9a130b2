// Tests of lib/optim: untangling, validity preservation, local vs global, exact
// vs finite-difference derivatives, boundary constraints, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>

#include <tbb/global_control.h>

#include "core/error.h"
#include "mesh/classified_tet_mesh.h"
#include "generate/hex_block.h"
#include "mesh/poly_mesh.h"
#include "optim/boundary.h"
#include "optim/objective.h"
#include "optim/optimize.h"
#include "quality/star_verdict.h"
#include "quality/stencil.h"
#include "raw_random_dual.h"

namespace polydual {
namespace {


// The box faces/edges a grid index lies on, as (axis, side) pairs.
std::set<std::pair<int, int>> box_constraints(const std::array<int, 3>& idx, int n) {
  std::set<std::pair<int, int>> s;
  for (int d = 0; d < 3; ++d)
    if (idx[d] == 0 || idx[d] == n) s.insert({d, idx[d] == n});
  return s;
}
// Same tags as hex_block(n, h, true).
std::int32_t face_tag(std::pair<int, int> c) { return 1 + 2 * c.first + c.second; }
std::int32_t edge_tag(const std::set<std::pair<int, int>>& cs) {
  std::int32_t t = 10;
  for (auto c : cs) t += face_tag(c) * (c.first == 0 ? 1 : (c.first == 1 ? 7 : 49));
  return t;
}

// The Kuhn tetrahedralisation (6 tets per cube) of the same grid as hex_block,
// with its box-face triangles classified {2, face tag} and box-edge segments
// {1, edge tag}: the "original facetisation" of the block's boundary.
ClassifiedTetMesh kuhn_primal(int n, double h = 1.0) {
  const int N = n + 1;
  std::vector<Point3> pts;
  std::vector<std::array<int, 3>> idx;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      for (int k = 0; k < N; ++k) {
        pts.push_back({i * h, j * h, k * h});
        idx.push_back({i, j, k});
      }
  auto vid = [&](int i, int j, int k) { return VertexId((i * N + j) * N + k); };
  std::vector<std::array<VertexId, 4>> tets;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& pm : perms) {
          std::array<int, 3> c{i, j, k};
          std::array<VertexId, 4> t;
          t[0] = vid(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[pm[s]];
            t[s + 1] = vid(c[0], c[1], c[2]);
          }
          const Vec3 a = pts[t[0].idx];
          if (dot(cross(pts[t[1].idx] - a, pts[t[2].idx] - a), pts[t[3].idx] - a) < 0) std::swap(t[1], t[2]);
          tets.push_back(t);
        }
  ClassifiedTetMesh m = TetMeshBuilder::build_topology("<kuhn>", pts, tets, std::vector<std::int32_t>(tets.size(), 1));
  auto& tc = TetMeshBuilder::triangle_face(m);
  for (std::size_t f = 0; f < m.num_triangles(); ++f) {
    std::set<std::pair<int, int>> common = box_constraints(idx[m.triangle(TriId(f))[0].idx], n);
    for (int v = 1; v < 3; ++v) {
      const auto cv = box_constraints(idx[m.triangle(TriId(f))[v].idx], n);
      std::set<std::pair<int, int>> out;
      std::set_intersection(common.begin(), common.end(), cv.begin(), cv.end(), std::inserter(out, out.begin()));
      common = out;
    }
    tc[f] = common.size() == 1 ? face_tag(*common.begin()) : TetMeshBuilder::kNoFace;
  }
  auto& ec = TetMeshBuilder::edge_class(m);
  for (std::size_t e = 0; e < m.num_edges(); ++e) {
    const auto a = box_constraints(idx[m.edge(EdgeId(e))[0].idx], n);
    const auto b = box_constraints(idx[m.edge(EdgeId(e))[1].idx], n);
    std::set<std::pair<int, int>> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::inserter(common, common.begin()));
    ec[e] = common.size() == 2 ? ModelRef{1, edge_tag(common)} : ModelRef{3, 1};
  }
  return m;
}

std::size_t invalid_cells(const PolyMesh& m) {
  const auto v = star_shaped_verdicts(m);
  return static_cast<std::size_t>(std::count_if(v.begin(), v.end(), [](auto x) { return !x.valid; }));
}

PolyMesh perturbed_block(int n, double amp, unsigned seed) {
  PolyMesh m = hex_block(n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amp, amp);
  for (std::size_t i = 0; i < m.num_points(); ++i)
    if (m.point_class[i].dim == 3) m.points[i] += Vec3{u(rng), u(rng), u(rng)};
  return m;
}

TEST(Optim, LocalUntanglesAVertexPushedThroughAFace) {
  for (Metric metric : {Metric::Q1, Metric::Q2})
    for (auto der : {OptimParams::Derivatives::FiniteDifference, OptimParams::Derivatives::Exact,
                     OptimParams::Derivatives::Analytic}) {
      PolyMesh m = hex_block(3);
      m.points[21] = {2.6, 1.2, 0.8};  // interior (1,1,1) pushed past (2,1,1)
      ASSERT_GT(invalid_cells(m), 0u);
      OptimParams p;
      p.metric = metric;
      p.derivatives = der;
      const OptimReport r = optimize(m, nullptr, p);
      EXPECT_GT(r.invalid_before, 0);
      EXPECT_EQ(r.invalid_after, 0) << metric_name(metric);
      EXPECT_EQ(invalid_cells(m), 0u);
      EXPECT_GT(r.vertex_updates, 0u);
    }
}

TEST(Optim, GlobalUntanglesAVertexPushedThroughAFace) {
  PolyMesh m = hex_block(3);
  m.points[21] = {2.6, 1.2, 0.8};
  OptimParams p;
  p.method = OptimParams::Method::Global;
  const OptimReport r = optimize(m, nullptr, p);
  EXPECT_GT(r.invalid_before, 0);
  EXPECT_EQ(r.invalid_after, 0);
  EXPECT_EQ(invalid_cells(m), 0u);
}

TEST(Optim, APassNeverTurnsAValidCellInvalid) {
  for (auto method : {OptimParams::Method::Local, OptimParams::Method::Global}) {
    PolyMesh m = perturbed_block(4, 0.3, 5);
    m.points[(1 * 5 + 1) * 5 + 1] = {2.4, 1.3, 0.9};
    m.points[(3 * 5 + 2) * 5 + 3] = {1.7, 2.6, 2.2};
    const auto v0 = star_shaped_verdicts(m);
    for (int it = 0; it < 4; ++it) {
      const auto before = star_shaped_verdicts(m);
      OptimParams p;
      p.method = method;
      p.max_iter = 1;
      p.newton_steps = 1;
      p.global_iterations_per_round = 5;
      const OptimReport r = optimize(m, nullptr, p);
      const auto after = star_shaped_verdicts(m);
      for (std::size_t c = 0; c < after.size(); ++c)
        if (before[c].valid) EXPECT_TRUE(after[c].valid) << c;
      for (std::size_t i = 1; i < r.iterations.size(); ++i)
        EXPECT_LE(r.iterations[i].invalid, r.iterations[i - 1].invalid);
    }
    EXPECT_GT(std::count_if(v0.begin(), v0.end(), [](auto x) { return !x.valid; }), 0);
  }
}

TEST(Optim, LocalAndGlobalReachTheSameOptimum) {
  const PolyMesh start = perturbed_block(4, 0.15, 9);
  const PolyMesh regular = hex_block(4);
  PolyMesh a = start, b = start;
  OptimParams p;
  p.tol = 1e-13;
  p.max_iter = 200;
  p.settle_move = 0;  // converge fully: no settled points skipped
  p.method = OptimParams::Method::Local;
  const OptimReport ra = optimize(a, nullptr, p);
  p.method = OptimParams::Method::Global;
  p.max_iter = 30;
  const OptimReport rb = optimize(b, nullptr, p);
  const double fa = ra.iterations.back().objective, fb = rb.iterations.back().objective;
  EXPECT_NEAR(fa / fb, 1.0, 1e-7);
  double da = 0, db = 0, dab = 0;
  for (std::size_t i = 0; i < a.num_points(); ++i) {
    da = std::max(da, norm(a.points[i] - regular.points[i]));
    db = std::max(db, norm(b.points[i] - regular.points[i]));
    dab = std::max(dab, norm(a.points[i] - b.points[i]));
  }
  // The perturbed block relaxes back to the regular block (its symmetric optimum).
  EXPECT_LT(da, 1e-4);
  EXPECT_LT(db, 1e-4);
  EXPECT_LT(dab, 1e-4);
  EXPECT_LT(ra.after.mean, ra.before.mean);
}

TEST(Optim, ExactFiniteDifferenceAndAdjointGradientsAgree) {
  const PolyMesh m = perturbed_block(3, 0.25, 2);
  const MeshStencil s = build_stencil(m, true);
  for (Metric metric : {Metric::Q1, Metric::Q2}) {
    const auto V0 = cell_reference_volumes(s, metric, m.points);
    for (std::size_t i = 0; i < m.num_points(); ++i) {
      if (m.point_class[i].dim != 3) continue;
      const PointId p(i);
      const LocalObjective obj{s, m.points.data(), V0.data(), metric, 50.0, p};
      using J = ceres::Jet<double, 3>;
      const J x[3] = {J(m.points[i].x, 0), J(m.points[i].y, 1), J(m.points[i].z, 2)};
      const J fj = obj(x);
      // Adjoint: sum over p's cells of the per-cell gradient at p's slot.
      Vec3 adj{};
      double fa = 0;
      for (std::uint32_t c : s.cells_of(p)) {
        std::vector<Vec3> g(s.points_of(c).size());
        fa += cell_energy_gradient(s, c, metric, m.points, V0[c], 50.0, g.data());
        const auto pts = s.points_of(c);
        adj += g[std::find(pts.begin(), pts.end(), p) - pts.begin()];
      }
      EXPECT_NEAR(fa / fj.a, 1.0, 1e-13);
      for (int d = 0; d < 3; ++d) {
        const double h = 1e-5;
        double xp[3] = {m.points[i].x, m.points[i].y, m.points[i].z}, xm[3] = {xp[0], xp[1], xp[2]};
        xp[d] += h;
        xm[d] -= h;
        const double fd = (obj(xp) - obj(xm)) / (2 * h);
        const double scale = std::max(1.0, std::fabs(fj.v[d]));
        EXPECT_NEAR(fd, fj.v[d], 1e-5 * scale) << i << " " << d;
        EXPECT_NEAR(adj[d], fj.v[d], 1e-10 * scale) << i << " " << d;
      }
    }
  }
}

TEST(Optim, AnalyticLocalDerivativesMatchJetAndItsDifferences) {
  // The closed-form Newton model (default derivatives): value bitwise equal to
  // LocalObjective, gradient = Jet gradient, Hessian = central differences of
  // the Jet gradient; on a mildly perturbed block and on a tangled one.
  for (double amp : {0.25, 0.45}) {
    const PolyMesh m = perturbed_block(3, amp, 7);
    const MeshStencil s = build_stencil(m);
    for (Metric metric : {Metric::Q1, Metric::Q2}) {
      const auto V0 = cell_reference_volumes(s, metric, m.points);
      for (std::size_t i = 0; i < m.num_points(); ++i) {
        if (m.point_class[i].dim != 3) continue;
        const PointId p(i);
        const LocalObjective obj{s, m.points.data(), V0.data(), metric, 50.0, p};
        double g[3], H[9];
        const double f = local_objective_derivatives(s, m.points.data(), V0.data(), metric, 50.0, p, g, H);
        const double x0[3] = {m.points[i].x, m.points[i].y, m.points[i].z};
        EXPECT_EQ(f, obj(x0)) << i;
        using J = ceres::Jet<double, 3>;
        auto jet_grad = [&](const double* x, double* out) {
          const J xj[3] = {J(x[0], 0), J(x[1], 1), J(x[2], 2)};
          const J fj = obj(xj);
          for (int d = 0; d < 3; ++d) out[d] = fj.v[d];
        };
        double gj[3];
        jet_grad(x0, gj);
        const double gs = std::max({1.0, std::fabs(gj[0]), std::fabs(gj[1]), std::fabs(gj[2])});
        for (int d = 0; d < 3; ++d) EXPECT_NEAR(g[d], gj[d], 1e-10 * gs) << i << " " << d;
        const double h = 1e-6;
        double hs = 1.0;
        for (int k = 0; k < 9; ++k) hs = std::max(hs, std::fabs(H[k]));
        for (int d = 0; d < 3; ++d) {
          double xp[3] = {x0[0], x0[1], x0[2]}, xm[3] = {x0[0], x0[1], x0[2]}, gp[3], gm[3];
          xp[d] += h;
          xm[d] -= h;
          jet_grad(xp, gp);
          jet_grad(xm, gm);
          for (int r = 0; r < 3; ++r)
            EXPECT_NEAR(H[3 * r + d], (gp[r] - gm[r]) / (2 * h), 1e-5 * hs) << i << " " << r << d;
        }
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) EXPECT_NEAR(H[3 * r + c], H[3 * c + r], 1e-12 * hs);
      }
    }
  }
}

// Lazy constraints (the local schemes): no search until a point's first
// ensure(), then the primitive of the eager search from the same position, and
// the same degrees of freedom from the start.
TEST(Optim, LazyConstraintsFindTheEagerPrimitives) {
  const ConvertResult r = raw_random_conversion(3, 300);
  const ClassifiedTetMesh& primal = r.primal;
  PolyMesh m = r.mesh;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Point3& x : m.points) x += Vec3{u(rng), u(rng), u(rng)};  // off the facets: a real search
  const ModelFacets facets = model_facets(primal);
  const BoundaryConstraints eager(facets, m);
  BoundaryConstraints lazy(facets, m, true);
  std::size_t searched = 0;
  for (std::size_t i = 0; i < m.num_points(); ++i) {
    const PointId p(i);
    ASSERT_EQ(lazy.dof(p), eager.dof(p)) << i;
    if (eager.dof(p) != 1 && eager.dof(p) != 2) continue;
    EXPECT_EQ(lazy.current(p), BoundaryConstraints::kNone) << i;
    lazy.ensure(p);
    EXPECT_EQ(lazy.current(p), eager.current(p)) << i;
    ++searched;
  }
  EXPECT_GT(searched, 10u);
}

TEST(Optim, BoundaryPointsStayOnTheOriginalFacetisation) {
  const ClassifiedTetMesh primal = kuhn_primal(3);
  for (auto method : {OptimParams::Method::Local, OptimParams::Method::Global}) {
    PolyMesh m = hex_block(3, 1.0, true);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    for (std::size_t i = 0; i < m.num_points(); ++i) {
      Point3& x = m.points[i];
      const int dim = m.point_class[i].dim;
      for (int d = 0; d < 3; ++d) {
        const bool on_bound = x[d] == 0.0 || x[d] == 3.0;
        if (dim == 3 || ((dim == 2 || dim == 1) && !on_bound)) x[d] += u(rng);
      }
    }
    const PolyMesh start = m;
    OptimParams p;
    p.method = method;
    const ModelFacets facets = model_facets(primal);
    const OptimReport r = optimize(m, &facets, p);
    EXPECT_EQ(r.invalid_after, 0);
    EXPECT_LT(r.after.mean, r.before.mean);
    const BoundaryConstraints bc(facets, start);
    int moved_surface = 0;
    for (std::size_t i = 0; i < m.num_points(); ++i) {
      const int dim = m.point_class[i].dim;
      if (dim == 0) EXPECT_EQ(m.points[i], start.points[i]);
      if (dim == 1 || dim == 2) {
        EXPECT_LT(bc.distance_to_entity(PointId(i), m.points[i]), 1e-12) << i;
        moved_surface += norm(m.points[i] - start.points[i]) > 1e-3;
      }
    }
    EXPECT_GT(moved_surface, 10);  // surface points did slide
  }
}

TEST(Optim, DeterministicAcrossRuns) {
  for (auto method : {OptimParams::Method::Local, OptimParams::Method::Global}) {
    PolyMesh a = perturbed_block(4, 0.3, 21), b = a;
    OptimParams p;
    p.method = method;
    p.max_iter = 3;
    const OptimReport ra = optimize(a, nullptr, p), rb = optimize(b, nullptr, p);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(ra.vertex_updates, rb.vertex_updates);
  }
}

// optimize(m, nullptr, p) with at most `threads` worker threads.
OptimReport optimize_on_threads(PolyMesh& m, const OptimParams& p, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  return optimize(m, nullptr, p);
}

// The sweeps run blocks of 256 consecutive points, the blocks of one colour
// in parallel: on a block with 15^3 free points (14 blocks, fewer colours, so
// some colour holds several blocks) one and two threads give the same points
// bit for bit with the default scheme.
TEST(Optim, BlockSweepsAreIdenticalForOneAndTwoThreads) {
  const PolyMesh start = perturbed_block(16, 0.3, 7);
  OptimParams p;
  p.max_iter = 3;
  PolyMesh a = start, b = start;
  const OptimReport ra = optimize_on_threads(a, p, 1), rb = optimize_on_threads(b, p, 2);
  EXPECT_GT(ra.vertex_updates, 3000u);
  EXPECT_LT(ra.colours, 14u) << "some colour must hold several blocks";
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(ra.vertex_updates, rb.vertex_updates);
}

TEST(Optim, ColouredSweepsAreIdenticalForOneAndTwoThreads) {
  // Parallel Gauss-Seidel over independent point sets: the result depends on the
  // colouring only, never on the thread count (default derivatives and fd).
  for (auto der : {OptimParams::Derivatives::Analytic, OptimParams::Derivatives::FiniteDifference}) {
    const PolyMesh start = [] {
      PolyMesh m = perturbed_block(6, 0.3, 33);
      m.points[(2 * 7 + 2) * 7 + 2] = {3.4, 2.2, 1.8};  // (2,2,2) pushed past (3,2,2)
      return m;
    }();
    OptimParams p;
    p.derivatives = der;
    p.max_iter = 4;
    PolyMesh a = start, b = start;
    const OptimReport ra = optimize_on_threads(a, p, 1), rb = optimize_on_threads(b, p, 2);
    EXPECT_GT(ra.invalid_before, 0);
    EXPECT_EQ(ra.invalid_after, 0);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(ra.vertex_updates, rb.vertex_updates);
    ASSERT_EQ(ra.iterations.size(), rb.iterations.size());
    for (std::size_t i = 0; i < ra.iterations.size(); ++i)
      EXPECT_EQ(ra.iterations[i].objective, rb.iterations[i].objective);
  }
}

TEST(Optim, UntanglingSweepsVisitOnlyTheTangledNeighbourhood) {
  // A regular block with one vertex pushed through a face: the first sweep
  // visits only the points of the invalid cells, fixes them, and the mesh ends
  // valid; the later full sweeps then visit everything.
  PolyMesh m = hex_block(6);
  m.points[(2 * 7 + 2) * 7 + 2] = {3.4, 2.2, 1.8};
  const auto v = star_shaped_verdicts(m);
  std::set<std::uint32_t> tangled_pts;
  const MeshStencil s = build_stencil(m);
  for (std::uint32_t c = 0; c < v.size(); ++c)
    if (!v[c].valid)
      for (PointId q : s.points_of(c))
        if (m.point_class[q.idx].dim == 3) tangled_pts.insert(q.idx);
  ASSERT_FALSE(tangled_pts.empty());
  OptimParams p;
  const OptimReport r = optimize(m, nullptr, p);
  ASSERT_GE(r.iterations.size(), 3u);
  EXPECT_GT(r.invalid_before, 0);
  EXPECT_EQ(r.invalid_after, 0);
  EXPECT_GT(r.iterations[1].visited, 0u);
  EXPECT_LE(r.iterations[1].visited, tangled_pts.size());
  // The first sweep (lagged model) and at most one more (full model, the
  // tangled neighbourhood only) untangle; then the first smoothing sweep
  // visits every free point.
  std::size_t valid_at = 1;
  while (valid_at < r.iterations.size() && r.iterations[valid_at].invalid > 0) ++valid_at;
  ASSERT_LE(valid_at, 2u);
  EXPECT_LE(r.iterations[valid_at].visited, tangled_pts.size() * 4);
  ASSERT_GT(r.iterations.size(), valid_at + 1);
  EXPECT_EQ(r.iterations[valid_at + 1].visited, 5u * 5u * 5u);
  // The paper's order (untangle_sweeps = 0) also untangles.
  PolyMesh m2 = hex_block(6);
  m2.points[(2 * 7 + 2) * 7 + 2] = {3.4, 2.2, 1.8};
  p.untangle_sweeps = 0;
  const OptimReport r2 = optimize(m2, nullptr, p);
  EXPECT_EQ(r2.iterations[1].visited, 5u * 5u * 5u);
  EXPECT_EQ(r2.invalid_after, 0);
}

TEST(Optim, MethodNoneOnlyReports) {
  PolyMesh m = perturbed_block(3, 0.2, 1);
  const PolyMesh start = m;
  OptimParams p;
  p.method = OptimParams::Method::None;
  const OptimReport r = optimize(m, nullptr, p);
  EXPECT_EQ(m.points, start.points);
  EXPECT_EQ(r.iterations.size(), 1u);
  EXPECT_EQ(r.vertex_updates, 0u);
  const std::string js = r.to_json().dump();
  for (const char* key : {"\"iterations\"", "\"invalid_before\"", "\"quality_after\"", "\"vertex_updates\""})
    EXPECT_NE(js.find(key), std::string::npos) << key;
}

TEST(Optim, Parsers) {
  EXPECT_EQ(parse_method("none"), OptimParams::Method::None);
  EXPECT_EQ(parse_method("local"), OptimParams::Method::Local);
  EXPECT_EQ(parse_method("global"), OptimParams::Method::Global);
  EXPECT_EQ(parse_metric("q1"), Metric::Q1);
  EXPECT_EQ(parse_metric("q2"), Metric::Q2);
  EXPECT_EQ(parse_derivatives("fd"), OptimParams::Derivatives::FiniteDifference);
  EXPECT_EQ(parse_derivatives("exact"), OptimParams::Derivatives::Exact);
  EXPECT_EQ(parse_derivatives("analytic"), OptimParams::Derivatives::Analytic);
  EXPECT_THROW(parse_method("newton"), UsageError);
  EXPECT_THROW(parse_metric("q3"), UsageError);
  EXPECT_THROW(parse_derivatives("jet"), UsageError);
}

}  // namespace
}  // namespace polydual
