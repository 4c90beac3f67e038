// SPDX-License-Identifier: BSD-3-Clause
// Cost of one whole collision, simulate() on data/scenes/default.toml (steel onto a wall), per
// integrator (cvode dense, cvode gmres, cvode schur, cvode with the soe-step history evaluator, ida) and rtol, without and with the history effect
// (sum of exponentials at its default tolerance). Counters: e, the integrator's steps, the state
// size and the last run's model construction time (included in the timing).
// One warm-up run per case keeps the one-off lookup tables and the exponential fit (cached per process by
// shared_soe_kernel) out of the timing: a single `imcol run` pays the fit, these figures do not.
// Usage: imcol_bench_collision [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>

#include "run/simulate.hpp"
#include "bench/bench_scenes.hpp"

namespace {

using namespace imcol;

void run_scene(benchmark::State& state, const Scene& sc) {
  RunResult r = simulate(sc);  // warm-up
  for (auto _ : state) {
    r = simulate(sc);
    benchmark::DoNotOptimize(r.rows.data());
  }
  const auto& s = r.summary;
  state.counters["e"] = s.e.value_or(-1.0);
  state.counters["steps"] = static_cast<double>(s.solver.stats.steps);
  state.counters["states"] = static_cast<double>(s.solver.stats.state_size);
  state.counters["setup_ms"] = 1e3 * s.setup_time_s;  // model construction, part of the time
}

}  // namespace

int main(int argc, char** argv) {
  struct Integrator { const char* name; const char* method; const char* linear_solver; bool needs_history; const char* evaluator; };
  const Integrator integrators[] = {{"cvode_dense", "cvode", "dense", false, "soe"},
                                    {"cvode_gmres", "cvode", "gmres", true, "soe"},  // gmres and schur need memory states
                                    {"cvode_schur", "cvode", "schur", true, "soe"},
                                    {"cvode_step", "cvode", "dense", true, "soe-step"},  // modes advanced per step, not states
                                    {"ida", "ida", "dense", false, "soe"}};
  for (bool history : {false, true})
    for (const auto& in : integrators)
      for (const char* rtol : {"1e-4", "1e-6", "1e-8", "1e-10"}) {
        if (in.needs_history && !history) continue;
        std::vector<Override> ov = {{"solver.integrator", in.method}, {"solver.linear_solver", in.linear_solver}, {"solver.rtol", rtol}};
        if (history) ov.push_back({"history.evaluator", std::string("\"") + in.evaluator + "\""});
        const Scene sc = bench::scene(bench::kWallScene, history, 0, ov);
        const std::string name = std::string("collision/") + in.name + "/rtol:" + rtol + "/history:" + (history ? "on" : "off");
        benchmark::RegisterBenchmark(name.c_str(), [sc](benchmark::State& st) { run_scene(st, sc); })->Unit(benchmark::kMillisecond);
      }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
