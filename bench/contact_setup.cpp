// SPDX-License-Identifier: BSD-3-Clause
// What building a contact law costs per run (a sweep builds one per point): the Hertz law, whose damping α(e_dry)
// (contact/hertz_law.hpp, Tsuji et al. 1992) is read off the shipped nodes of e(α), against the ramp law (no setup)
// and one dimensionless impact (what solving for α costs per trial, several per e_dry) in the same run:
//   contact_setup/hertz/new_e_dry   every law a new e_dry (a sweep over e_dry)
//   contact_setup/hertz/same_e_dry  every law the same e_dry (a sweep over anything else)
//   contact_setup/ramp              the baseline
//   contact_setup/tsuji_impact      one impact at α = 0.05 (e ≈ 0.97)
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
    e -= 1e-7;  // a new value every law
    HertzLaw law(steel_pair(e));
    benchmark::DoNotOptimize(law.eta());
  }
}

void hertz_same_e_dry(benchmark::State& state) {
  for (auto _ : state) {
    HertzLaw law(steel_pair(0.9));
    benchmark::DoNotOptimize(law.eta());
  }
}

void one_impact(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(tsuji_impact(0.05).e);
}

void ramp(benchmark::State& state) {
  for (auto _ : state) {
    RampLaw law(steel_pair(0.9));
    benchmark::DoNotOptimize(&law);
  }
}

}  // namespace

BENCHMARK(hertz_new_e_dry)->Name("contact_setup/hertz/new_e_dry")->Unit(benchmark::kMicrosecond);
BENCHMARK(hertz_same_e_dry)->Name("contact_setup/hertz/same_e_dry")->Unit(benchmark::kMicrosecond);
BENCHMARK(ramp)->Name("contact_setup/ramp")->Unit(benchmark::kMicrosecond);
BENCHMARK(one_impact)->Name("contact_setup/tsuji_impact")->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
