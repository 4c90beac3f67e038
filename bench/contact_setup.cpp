// SPDX-License-Identifier: BSD-3-Clause
// What building a contact law costs per run (a sweep builds one per point): the Hertz law, whose damping α(e_dry)
// (contact/hertz_law.hpp, Tsuji et al. 1992) is solved by integrating a dimensionless impact once per e_dry in a
// process, against the ramp law (no setup) in the same run:
//   contact_setup/hertz/new_e_dry   every law a new e_dry (the solve each time: a sweep over e_dry)
//   contact_setup/hertz/same_e_dry  every law the same e_dry (remembered: a sweep over anything else)
//   contact_setup/ramp              the baseline
// Usage: imcol_bench_contact_setup [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include "contact/hertz_law.hpp"
#include "contact/ramp_law.hpp"

namespace {

using namespace imcol::contact;

/// A 12.7 mm steel sphere on a wall (kg, Pa, m).
ContactPair steel_pair(double e_dry) { return {0.0084, 1.0e11, 0.00635, e_dry, 1.27e-4, 0.0127, 0.01, 0, "bench"}; }

void hertz_new_e_dry(benchmark::State& state) {
  double e = 0.97;
  for (auto _ : state) {
    e -= 1e-7;  // never seen before: solved
    HertzLaw law(steel_pair(e));
    benchmark::DoNotOptimize(law.eta());
  }
}

void hertz_same_e_dry(benchmark::State& state) {
  HertzLaw warm(steel_pair(0.9));
  benchmark::DoNotOptimize(warm.eta());
  for (auto _ : state) {
    HertzLaw law(steel_pair(0.9));
    benchmark::DoNotOptimize(law.eta());
  }
}

void ramp(benchmark::State& state) {
  for (auto _ : state) {
    RampLaw law(steel_pair(0.9));
    benchmark::DoNotOptimize(&law);
  }
}

}  // namespace

BENCHMARK(hertz_new_e_dry)->Name("contact_setup/hertz/new_e_dry")->Unit(benchmark::kMillisecond);
BENCHMARK(hertz_same_e_dry)->Name("contact_setup/hertz/same_e_dry")->Unit(benchmark::kMicrosecond);
BENCHMARK(ramp)->Name("contact_setup/ramp")->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
