// SPDX-License-Identifier: BSD-3-Clause
// The history memory's outputs inside an accepted step (contact/step_outputs.hpp, SphereHistory::accept_step): the
// interpolant reproduces quartics and its error estimate follows the cubic's true error; on a smooth velocity the
// interpolated outputs agree with the exact ones within the memory's own error and leave the memory as it was; a restart's first step is exact; and
// in a run the trajectory does not move while the rows' history force stays with the exact one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "contact/history_force.hpp"
#include "contact/step_outputs.hpp"
#include "core/data_dir.hpp"
#include "core/scene.hpp"
#include "run/simulate.hpp"

using namespace imcol;
using contact::StepOutputs;

namespace {

/// The cubic Hermite through (f, f') at 0 and h, at x.
double hermite(double h, StepOutputs::End a, StepOutputs::End b, double x) {
  const double s = x / h, r = 1 - s;
  return (1 + 2 * s) * r * r * a.value + s * r * r * h * a.slope + s * s * (3 - 2 * s) * b.value - s * s * r * h * b.slope;
}

}  // namespace

TEST(StepOutputs, AQuarticIsReproducedAndACubicNeedsNoCorrection) {
  const double h = 0.3;
  auto quartic = [](double x) { return 1.5 - 2 * x + 0.7 * x * x - 3 * x * x * x + 5 * x * x * x * x; };
  auto dquartic = [](double x) { return -2 + 1.4 * x - 9 * x * x + 20 * x * x * x; };
  const StepOutputs q(h, {quartic(0), dquartic(0)}, {quartic(h), dquartic(h)}, 0.4 * h, quartic(0.4 * h), 1.0);
  ASSERT_TRUE(q.accepted());
  for (int k = 0; k <= 20; ++k) EXPECT_NEAR(q.value(k * h / 20), quartic(k * h / 20), 1e-14) << k;
  auto cubic = [](double x) { return 1.5 - 2 * x + 0.7 * x * x - 3 * x * x * x; };
  auto dcubic = [](double x) { return -2 + 1.4 * x - 9 * x * x; };
  EXPECT_LT(StepOutputs::estimate(h, {cubic(0), dcubic(0)}, {cubic(h), dcubic(h)}, 0.6 * h, cubic(0.6 * h)), 1e-15);
  // The check lag must lie within [h/4, 3h/4]: outside, no estimate and no interpolant.
  EXPECT_TRUE(std::isinf(StepOutputs::estimate(h, {cubic(0), dcubic(0)}, {cubic(h), dcubic(h)}, 0.1 * h, cubic(0.1 * h))));
  EXPECT_FALSE(StepOutputs(h, {cubic(0), dcubic(0)}, {cubic(h), dcubic(h)}, 0.9 * h, cubic(0.9 * h), 1.0).accepted());
}

TEST(StepOutputs, TheEstimateFollowsTheCubicsErrorAndDecidesByTheTolerance) {
  // f = 1/√(x + 1) on [0, h], as the memory after a sharp rebound: from a gentle step to one as long as the distance
  // to the singularity. The estimate from the miss at Δc is within 2× of the cubic's largest error, and the quartic
  // that replaces it errs by no more than the estimate.
  auto f = [](double x) { return 1 / std::sqrt(x + 1); };
  auto df = [](double x) { return -0.5 / ((x + 1) * std::sqrt(x + 1)); };
  for (double h : {0.05, 0.3, 1.0}) {
    for (double sc : {0.5, 0.3, 0.7}) {
      SCOPED_TRACE("h = " + std::to_string(h) + ", Δc/h = " + std::to_string(sc));
      const StepOutputs::End a{f(0), df(0)}, b{f(h), df(h)};
      const double est = StepOutputs::estimate(h, a, b, sc * h, f(sc * h));
      double cubic = 0, quartic = 0;
      const StepOutputs s(h, a, b, sc * h, f(sc * h), est);
      for (int k = 1; k < 200; ++k) {
        const double x = k * h / 200;
        cubic = std::max(cubic, std::abs(hermite(h, a, b, x) - f(x)));
        quartic = std::max(quartic, std::abs(s.value(x) - f(x)));
      }
      EXPECT_GT(est, 0.5 * cubic);
      EXPECT_LT(est, 2.0 * cubic);
      EXPECT_LE(quartic, est);
      EXPECT_TRUE(s.accepted());
      EXPECT_FALSE(StepOutputs(h, a, b, sc * h, f(sc * h), 0.5 * est).accepted());
    }
  }
}

namespace {

/// A 1 mm sphere in water with U(t) = 0.1 cos(2π t/T), T = 10 ms, driven through steps as the integrator does (a trial
/// evaluation at the end, the step accepted, outputs inside it, the memory advanced); the steps vary by ±30 %.
struct DrivenMemory {
  explicit DrivenMemory(bool interpolate) : h(options(interpolate), 0.0005, 1e-3, 1000.0, u(0)) {
    std::vector<double> z(h.modes(), 0.0);
    h.reset_memory(0.0, z);
    h.advance_memory(0.0, u(0), true);
  }
  static contact::HistoryOptions options(bool interpolate) {
    contact::HistoryOptions o;
    o.evaluator = HistoryEvaluator::soe_step;
    o.min_lag = 1e-7;
    o.horizon = 0.1;
    o.interpolate_outputs = interpolate;
    o.output_rtol = 1e-6;
    o.output_atol = 1e-12;
    return o;
  }
  static double u(double t) { return 0.1 * std::cos(2 * M_PI * t / 0.01); }
  double force(double t) const { return h.evaluate(t, u(t), 1.0, {}).force; }
  /// One step of length dt: the trial at its end, then the outputs at the fractions `at`, then the advance (restart:
  /// a re-initialisation there instead). Returns the outputs.
  std::vector<double> step(double dt, const std::vector<double>& at, bool restart = false) {
    const double t1 = t + dt;
    force(t1);
    h.accept_step(t1, u(t1));
    std::vector<double> out;
    for (double s : at) out.push_back(force(t + s * dt));
    h.advance_memory(t1, u(t1), restart);
    t = t1;
    return out;
  }
  contact::SphereHistory h;
  double t = 0;
};

}  // namespace

TEST(StepOutputs, TheMemorysInterpolatedOutputsAgreeWithItsExactOnesAndLeaveItUntouched) {
  DrivenMemory interp(true), exact(false);
  const std::vector<double> at = {0.5, 0.17, 0.61, 0.93};  // the energy quadrature's middle and three rows
  double worst = 0, peak = 0;
  for (int k = 0; k < 400; ++k) {
    const double dt = 2e-4 * (1 + 0.3 * std::sin(0.7 * k));
    const auto a = interp.step(dt, at), b = exact.step(dt, at);
    for (std::size_t i = 0; i < a.size(); ++i) {
      worst = std::max(worst, std::abs(a[i] - b[i]));
      peak = std::max(peak, std::abs(b[i]));
    }
    // A trial evaluation inside the next step (the solver's) sees the same memory in both, to the bit.
    EXPECT_EQ(interp.force(interp.t + 0.3 * dt), exact.force(exact.t + 0.3 * dt)) << "step " << k;
  }
  std::printf("  driven memory: interpolated %ld, exact %ld outputs; largest difference %.2e of the peak force\n",
              interp.h.interpolated_outputs(), interp.h.exact_outputs(), worst / peak);
  EXPECT_EQ(exact.h.interpolated_outputs(), 0);
  EXPECT_GT(interp.h.interpolated_outputs(), 0.75 * 4 * 400);
  // The exact outputs carry the memory's own error: U' jumps by a little from one step's polynomial to the next, and
  // the kernel turns the jump into a √Δ at each step's start. The interpolant is accepted within that error's
  // estimate (the step's memory with a polynomial one degree lower), 1e-3 to 1e-4 of the force at these steps (T/50).
  EXPECT_LT(worst, 3e-4 * peak);
}

TEST(StepOutputs, TheFirstStepAfterARestartIsEvaluatedExactly) {
  DrivenMemory interp(true), exact(false);
  const std::vector<double> at = {0.5, 0.25};
  for (int k = 0; k < 20; ++k) interp.step(2e-4, at), exact.step(2e-4, at);
  interp.step(2e-4, at, true), exact.step(2e-4, at, true);  // an event: U' may jump at its end
  const long before = interp.h.interpolated_outputs();
  const auto a = interp.step(2e-4, at), b = exact.step(2e-4, at);
  EXPECT_EQ(interp.h.interpolated_outputs(), before);  // no slope at the restart: every output exact
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
}

TEST(StepOutputs, ARunsTrajectoryDoesNotMoveAndItsRowsKeepTheExactHistoryForce) {
  for (const char* name : {"seed_run2", "default"}) {
    SCOPED_TRACE(name);
    auto run = [&](bool interpolate) {
      return simulate(load_scene(data_dir() + "/scenes/" + name + ".toml",
                                 {{"solver.rtol", "1e-6"}, {"history.interpolate_outputs", interpolate ? "true" : "false"}}));
    };
    const RunResult a = run(true), b = run(false);
    // The model block says how the outputs were taken.
    const std::string said_a = a.summary_json["model"]["history.outputs"], said_b = b.summary_json["model"]["history.outputs"];
    EXPECT_EQ(said_a.rfind("0 interpolated", 0), std::string::npos) << said_a;
    EXPECT_EQ(said_b.rfind("0 interpolated, ", 0), 0u) << said_b;
    EXPECT_EQ(a.summary_json["e"].get<double>(), b.summary_json["e"].get<double>());
    EXPECT_EQ(a.summary_json["solver"]["steps"].get<long>(), b.summary_json["solver"]["steps"].get<long>());
    ASSERT_EQ(a.rows.size(), b.rows.size());
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      if (a.columns[c].rfind("f_hist", 0) != 0) continue;
      double worst = 0, peak = 0;
      for (std::size_t r = 0; r < a.rows.size(); ++r) {
        worst = std::max(worst, std::abs(a.rows[r][c] - b.rows[r][c]));
        peak = std::max(peak, std::abs(b.rows[r][c]));
      }
      std::printf("  %s %s: rows' history force within %.2e of its peak\n", name, a.columns[c].c_str(), worst / peak);
      EXPECT_LT(worst, 1e-4 * peak) << a.columns[c];
    }
    const auto& pa = a.summary_json["energy_budget"]["phases"];
    const auto& pb = b.summary_json["energy_budget"]["phases"];
    ASSERT_EQ(pa.size(), pb.size());
    for (std::size_t k = 0; k < pa.size(); ++k)
      EXPECT_NEAR(pa[k]["closure_per_impact_energy"].get<double>(), pb[k]["closure_per_impact_energy"].get<double>(), 1e-7);
  }
}

TEST(StepOutputs, TheEndAdvancedAtAcceptanceIsTheAdvanceOfThatEnd) {
  // accept_step moves the modes to the accepted end ahead of time (with S and S' there, in one pass); advance_memory
  // takes them only at that time and velocity. Against a memory never told of acceptance: the same to the bit, also
  // where an event changed the velocity between acceptance and advance (a restart there).
  DrivenMemory a(true), b(true);
  int events = 0;
  for (int k = 0; k < 200; ++k) {
    const double dt = 2e-4 * (1 + 0.3 * std::sin(0.7 * k));
    const double t1 = a.t + dt;
    EXPECT_EQ(a.force(t1), b.force(t1)) << "trial, step " << k;
    a.h.accept_step(t1, DrivenMemory::u(t1));
    const bool event = k % 37 == 36;
    const double u_end = event ? 0.9 * DrivenMemory::u(t1) : DrivenMemory::u(t1);
    events += event;
    a.h.advance_memory(t1, u_end, event);
    b.h.advance_memory(t1, u_end, event);
    a.t = b.t = t1;
    EXPECT_EQ(a.force(t1 + 0.3 * dt), b.force(t1 + 0.3 * dt)) << "inside the next step, step " << k;
  }
  EXPECT_EQ(events, 5);
}
