// Optimiser benchmark (SPEC §12): local Newton (analytic default, finite-difference
// and exact derivatives) and global L-BFGS on a perturbed block of 22^3 = 10,648 hex
// cells with some cells tangled. Counters: vertex updates per second, invalid
// cells before/after, time to the last iteration, final mean quality.
//   build-perf/bench/optim_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <random>

#include "mesh/poly_mesh.h"
#include "optim/optimize.h"

namespace polydual {
namespace {

// Same helper as tests/optim_test.cpp (boundary points fixed).
PolyMesh hex_block(int n, double h = 1.0, bool classify_boundary = false) {
  PolyMesh m;
  const int N = n + 1;
  auto pid = [&](int i, int j, int k) { return PointId((i * N + j) * N + k); };
  auto cid = [&](int i, int j, int k) { return CellId((i * n + j) * n + k); };
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      for (int k = 0; k < N; ++k) {
        const int idx[3] = {i, j, k};
        int on = 0, face_tag = 0, edge_tag = 10;
        for (int d = 0; d < 3; ++d)
          if (idx[d] == 0 || idx[d] == n) {
            ++on;
            face_tag = 1 + 2 * d + (idx[d] == n);
            edge_tag += (1 + 2 * d + (idx[d] == n)) * (d == 0 ? 1 : (d == 1 ? 7 : 49));
          }
        ModelRef cls{3, 1};
        if (on > 0) cls = classify_boundary ? (on == 1 ? ModelRef{2, face_tag}
                                               : on == 2 ? ModelRef{1, edge_tag} : ModelRef{0, edge_tag})
                                            : ModelRef{0, 0};
        m.add_point({i * h, j * h, k * h}, cls);
      }
  std::vector<std::vector<HalfFace>> cells(static_cast<std::size_t>(n) * n * n);
  auto add = [&](std::array<PointId, 4> loop, bool has_lo, CellId lo, bool has_hi, CellId hi,
                 std::int32_t tag) {
    if (has_lo) {
      const FaceId f = m.add_face(loop, lo, has_hi ? hi : CellId::invalid(),
                                  has_hi ? FaceKind::Interior : FaceKind::External, has_hi ? 0 : tag);
      cells[lo.idx].push_back(HalfFace(f, 0));
      if (has_hi) cells[hi.idx].push_back(HalfFace(f, 1));
    } else {
      std::reverse(loop.begin(), loop.end());
      const FaceId f = m.add_face(loop, hi, CellId::invalid(), FaceKind::External, tag);
      cells[hi.idx].push_back(HalfFace(f, 0));
    }
  };
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c) {
        // Loops with right-hand normal +x, +y, +z; the cell below the plane owns them.
        add({pid(a, b, c), pid(a, b + 1, c), pid(a, b + 1, c + 1), pid(a, b, c + 1)}, a > 0,
            a > 0 ? cid(a - 1, b, c) : CellId(), a < n, a < n ? cid(a, b, c) : CellId(), a == 0 ? 1 : 2);
        add({pid(b, a, c), pid(b, a, c + 1), pid(b + 1, a, c + 1), pid(b + 1, a, c)}, a > 0,
            a > 0 ? cid(b, a - 1, c) : CellId(), a < n, a < n ? cid(b, a, c) : CellId(), a == 0 ? 3 : 4);
        add({pid(b, c, a), pid(b + 1, c, a), pid(b + 1, c + 1, a), pid(b, c + 1, a)}, a > 0,
            a > 0 ? cid(b, c, a - 1) : CellId(), a < n, a < n ? cid(b, c, a) : CellId(), a == 0 ? 5 : 6);
      }
  for (const auto& hf : cells) m.add_cell(hf, 1, VertexId::invalid());
  return m;
}

const PolyMesh& perturbed_block() {
  static const PolyMesh m = [] {
    PolyMesh b = hex_block(22);
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> u(-0.4, 0.4);
    for (std::size_t i = 0; i < b.num_points(); ++i)
      if (b.point_class[i].dim == 3) b.points[i] += Vec3{u(rng), u(rng), u(rng)};
    return b;
  }();
  return m;
}

void run(benchmark::State& state, OptimParams p) {
  p.metric = state.range(0) == 1 ? Metric::Q1 : Metric::Q2;
  OptimReport r;
  for (auto _ : state) {
    state.PauseTiming();
    PolyMesh m = perturbed_block();
    state.ResumeTiming();
    r = optimize(m, nullptr, p);
    benchmark::DoNotOptimize(m.points.data());
  }
  state.counters["cells"] = static_cast<double>(perturbed_block().num_cells());
  state.counters["invalid_before"] = r.invalid_before;
  state.counters["invalid_after"] = r.invalid_after;
  state.counters["iterations"] = static_cast<double>(r.iterations.size() - 1);
  state.counters["vertex_updates"] = static_cast<double>(r.vertex_updates);
  state.counters["updates_per_s"] = r.seconds > 0 ? static_cast<double>(r.vertex_updates) / r.seconds : 0;
  state.counters["seconds"] = r.seconds;
  // Time at which the invalid count first reached its final value.
  double t_final_invalid = 0;
  for (const auto& it : r.iterations)
    if (it.invalid == static_cast<std::size_t>(r.invalid_after)) { t_final_invalid = it.seconds; break; }
  state.counters["s_to_final_invalid"] = t_final_invalid;
  state.counters["mean_q_before"] = r.before.mean;
  state.counters["mean_q_after"] = r.after.mean;
}

// Default local scheme: analytic Newton model, coloured parallel sweeps, active set.
void BM_LocalAnalytic(benchmark::State& s) { run(s, OptimParams{}); }
void BM_LocalFD(benchmark::State& s) {
  OptimParams p;
  p.derivatives = OptimParams::Derivatives::FiniteDifference;
  run(s, p);
}
void BM_LocalExact(benchmark::State& s) {
  OptimParams p;
  p.derivatives = OptimParams::Derivatives::Exact;
  run(s, p);
}
void BM_Global(benchmark::State& s) {
  OptimParams p;
  p.method = OptimParams::Method::Global;
  run(s, p);
}

BENCHMARK(BM_LocalAnalytic)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_LocalFD)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_LocalExact)->Arg(1)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_Global)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace polydual

BENCHMARK_MAIN();
