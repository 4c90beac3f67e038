// SPDX-License-Identifier: BSD-3-Clause
// Output samples of the integrator driver (integrators/sundials_driver.cpp): every output time k·dt is sampled, under
// that time, when the solver stops on a breakpoint grid kΔ (the direct history evaluator) or at advance() targets
// n·Δt (a coupled run's flow steps) that fall a rounding short of it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "integrators/integrator.hpp"
#include "tests/unit_ramp.hpp"

namespace {

using namespace imcol;

/// y' = 1 from y = 0 up to t_end, with breakpoints on the grid kΔ when Δ > 0.
class Ramp : public test::UnitRamp {
 public:
  Ramp(double t_end, double grid) : t_end_(t_end), grid_(grid) {}
  std::vector<RootSpec> roots() const override { return {}; }
  void root_values(double, std::span<const double>, std::span<double>) override {}
  EventAction on_roots(std::span<const std::size_t>, double, std::span<double>) override { return EventAction::proceed; }
  double stop_time() const override { return t_end_; }
  double max_step(double, std::span<const double>) const override { return grid_ > 0 ? grid_ : t_end_; }
  double next_breakpoint(double) const override {
    return grid_ > 0 ? grid_ * static_cast<double>(points_) : std::numeric_limits<double>::infinity();
  }
  void at_breakpoint(double, std::span<const double>) override { ++points_; }
  long points() const { return points_ - 1; }

 private:
  double t_end_, grid_;
  long points_ = 1;
};

/// The samples off events: their times and |y − t|.
struct Samples : Observer {
  std::vector<double> t;
  double worst = 0;
  void sample(double time, std::span<const double> y, bool at_event) override {
    if (at_event) return;
    t.push_back(time);
    worst = std::max(worst, std::abs(y[0] - time));
  }
};

/// The output times k·dt (k = 1, 2, …) before t_end, as the driver computes them, and t_end.
std::vector<double> output_times(double dt, double t_end) {
  std::vector<double> t;
  for (long k = 1; k * dt < t_end * (1 - 1e-12); ++k) t.push_back(k * dt);
  t.push_back(t_end);
  return t;
}

IntegratorSettings settings(IntegratorMethod method, double dt) {
  IntegratorSettings st;
  st.method = method;
  st.output_dt = dt;
  return st;
}

TEST(OutputSamples, EveryOutputTimeIsSampledOnABreakpointGrid) {
  // Δ a fraction of dt (output.dt 0.2 ms as the rising sphere), and the double below it (the rising sphere's direct
  // step is 6.666666666666666e-05, one below 2e-4/3): kΔ falls a rounding short of the output times at many of them.
  const double dt = 2e-4, t_end = 0.0666667;
  for (const auto method : {IntegratorMethod::cvode, IntegratorMethod::ida})
    for (const double n : {1.0, 3.0, 5.0, 7.0, 10.0})
      for (const double grid : {dt / n, std::nextafter(dt / n, 0.0)}) {
        SCOPED_TRACE(std::string(to_string(method)) + ", grid " + std::to_string(grid));
        Ramp sys(t_end, grid);
        Samples obs;
        integrate(sys, settings(method, dt), obs);
        EXPECT_EQ(obs.t, output_times(dt, t_end));
        EXPECT_LT(obs.worst, 1e-12);
        EXPECT_EQ(sys.points(), static_cast<long>(std::floor(t_end / grid)));  // every grid point recorded
      }
}

TEST(OutputSamples, EveryOutputTimeIsSampledBetweenAdvanceTargets) {
  // Targets n·Δt with Δt = 70 µs and output.dt = 0.2 ms (as coupled/free_fall_stokes): 20 Δt falls a rounding short
  // of 7 dt at some of them.
  const double dt = 2e-4, step = 7e-5, t_end = 0.03;
  for (const auto method : {IntegratorMethod::cvode, IntegratorMethod::ida}) {
    SCOPED_TRACE(to_string(method));
    Ramp sys(t_end, 0);
    Samples obs;
    Integrator it(sys, settings(method, dt), obs);
    for (long n = 1; !it.finished(); ++n) it.advance(static_cast<double>(n) * step);
    EXPECT_EQ(obs.t, output_times(dt, t_end));
    EXPECT_LT(obs.worst, 1e-12);
  }
}

}  // namespace
