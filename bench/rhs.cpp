// SPDX-License-Identifier: BSD-3-Clause
// Cost of one right-hand-side evaluation of the collision model (model/collision_model.hpp),
// for a wall and a pair scene, without the history effect and with it at several mode counts.
// Items/s = right-hand sides per second. Usage: imcol_bench_rhs [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <string>
#include <utility>
#include <vector>

#include "bench/bench_scenes.hpp"
#include "model/collision_model.hpp"

namespace {

using namespace imcol;

/// modes: -1 no history, 0 history at its default tolerance, n > 0 that many exponentials per sphere.
void rhs(benchmark::State& state, const char* file, long modes) {
  const Scene sc = bench::scene(file, modes >= 0, modes);
  model::CollisionModel model(sc);
  std::vector<double> y(model.size()), ydot(model.size());
  model.initial_state(y);
  for (std::size_t i = model.core_size(); i < y.size(); ++i) y[i] = 1e-3;  // a memory that is not empty
  for (auto _ : state) {
    model.rhs(0.0, y, ydot);
    benchmark::DoNotOptimize(ydot.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["states"] = static_cast<double>(model.size());
}

}  // namespace

int main(int argc, char** argv) {
  for (const auto& [what, file] : {std::pair{"wall", bench::kWallScene}, std::pair{"pair", bench::kPairScene}})
    for (long modes : {-1L, 0L, 20L, 40L, 80L}) {
      const std::string name = std::string("rhs/") + what + "/" +
                               (modes < 0 ? "no_history" : modes == 0 ? "history_default" : "modes:" + std::to_string(modes));
      benchmark::RegisterBenchmark(name.c_str(), [file = file, modes](benchmark::State& st) { rhs(st, file, modes); });
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
