// Cost of one whole collision, simulate() on data/scenes/default.toml (steel onto a wall), per
// integrator (cvode dense, cvode gmres, cvode schur, ida) and rtol, without and with the history effect
// (sum of exponentials at its default tolerance). Counters: e, the integrator's steps, the state
// size and the last run's model construction time (included in the timing).
// One warm-up run per case keeps the one-off lookup tables out of the timing.
// Usage: imcol_bench_collision [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>

#include "run/simulate.hpp"
#include "bench/bench_scenes.hpp"

namespace {

using namespace imcol;

void run(benchmark::State& state, const Scene& sc) {
  RunResult r = simulate(sc);  // warm-up
  for (auto _ : state) {
    r = simulate(sc);
    benchmark::DoNotOptimize(r.rows.data());
  }
  const auto& s = r.summary;
  state.counters["e"] = s["e"].is_null() ? -1.0 : s["e"].get<double>();
  state.counters["steps"] = static_cast<double>(s["solver"]["steps"].get<long>());
  state.counters["states"] = static_cast<double>(s["solver"]["state_size"].get<long>());
  state.counters["setup_ms"] = 1e3 * s["setup_time_s"].get<double>();  // model construction, part of the time
}

}  // namespace

int main(int argc, char** argv) {
  struct Integrator { const char* name; const char* method; const char* linear_solver; bool needs_history; };
  const Integrator integrators[] = {{"cvode_dense", "cvode", "dense", false},
                                    {"cvode_gmres", "cvode", "gmres", true},  // gmres and schur need memory states
                                    {"cvode_schur", "cvode", "schur", true},
                                    {"ida", "ida", "dense", false}};
  for (bool history : {false, true})
    for (const auto& in : integrators)
      for (const char* rtol : {"1e-4", "1e-6", "1e-8", "1e-10"}) {
        if (in.needs_history && !history) continue;
        const Scene sc = bench::scene(bench::kWallScene, history, 0,
                                      {{"solver.integrator", in.method}, {"solver.linear_solver", in.linear_solver},
                                       {"solver.rtol", rtol}});
        const std::string name = std::string("collision/") + in.name + "/rtol:" + rtol + "/history:" + (history ? "on" : "off");
        benchmark::RegisterBenchmark(name.c_str(), [sc](benchmark::State& st) { run(st, sc); })->Unit(benchmark::kMillisecond);
      }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
