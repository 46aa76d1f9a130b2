// Optimiser benchmark (design §12): local Newton (analytic default, finite-difference
// and exact derivatives) and global L-BFGS on a perturbed block of 22^3 = 10,648 hex
// cells with some cells tangled. Counters: vertex updates per second, invalid
// cells before/after, time to the last iteration, final mean quality.
//   build-perf/bench/optim_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <random>

#include "generate/hex_block.h"
#include "mesh/poly_mesh.h"
#include "optim/optimize.h"

namespace polydual {
namespace {


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
