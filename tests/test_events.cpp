// SPDX-License-Identifier: BSD-3-Clause
// Event handling in the integrator driver (integrators/sundials_driver.cpp): a root function that is exactly zero
// at an event and stays so over the solver's smallest step.
#include <gtest/gtest.h>

#include "integrators/integrator.hpp"
#include "tests/unit_ramp.hpp"

namespace {

using namespace imcol;

/// y' = 1 from y = 0; one root g = y − 0.5 that sits at exactly 0 over a plateau of 1e-9 (as a slowly moving gap
/// whose change over the solver's smallest step is below rounding), reported as a diagnostic (proceed), and a
/// second ordinary root g = y − 0.75.
class PlateauRoot : public test::UnitRamp {
 public:
  std::vector<RootSpec> roots() const override { return {{"plateau", 0}, {"y=0.75", 0}}; }
  void root_values(double, std::span<const double> y, std::span<double> g) override {
    g[0] = (y[0] >= 0.5 && y[0] <= 0.5 + 1e-9) ? 0.0 : y[0] - 0.5;
    g[1] = y[0] - 0.75;
  }
  EventAction on_roots(std::span<const std::size_t> found, double t, std::span<double>) override {
    for (std::size_t i : found) events.push_back({i, t});
    return EventAction::proceed;
  }
  double stop_time() const override { return 1.0; }
  double max_step(double, std::span<const double>) const override { return 0.1; }
  std::vector<std::pair<std::size_t, double>> events;
};

class NullObserver : public Observer {
 public:
  void sample(double, std::span<const double>, bool) override {}
};

void runs_through_a_flat_root(IntegratorMethod method) {
  PlateauRoot sys;
  NullObserver obs;
  IntegratorSettings st;
  st.method = method;
  st.output_dt = 0.01;
  SolverStats stats;
  ASSERT_NO_THROW(stats = integrate(sys, st, obs));  // was: CV_ILL_INPUT / IDA_ILL_INPUT "Root found at and very near t"
  ASSERT_EQ(sys.events.size(), 2u);
  EXPECT_EQ(sys.events[0].first, 0u);
  EXPECT_NEAR(sys.events[0].second, 0.5, 1e-8);
  EXPECT_EQ(sys.events[1].first, 1u);
  EXPECT_NEAR(sys.events[1].second, 0.75, 1e-8);
}

TEST(Events, ARootExactlyZeroAtItsEventDoesNotStopCvode) { runs_through_a_flat_root(IntegratorMethod::cvode); }
TEST(Events, ARootExactlyZeroAtItsEventDoesNotStopIda) { runs_through_a_flat_root(IntegratorMethod::ida); }

}  // namespace
