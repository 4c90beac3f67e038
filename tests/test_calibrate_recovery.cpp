// SPDX-License-Identifier: BSD-3-Clause
// Recovery: the calibration finds the parameters that made a synthetic measurement (gg3462's own model, with noise
// of a stated size and a clock offset), from a distant start.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>

#include "calibrate/fit_parameter.hpp"
#include "calibrate/objective.hpp"
#include "calibrate/search.hpp"
#include "core/materials.hpp"
#include "run/measured_run.hpp"
#include "tests/calibrate_runner.hpp"

using namespace imcol;
using namespace imcol::calib;
using imcol::test::gg3462;


namespace {

/// gg3462 at δ_SS = 0.024 seen by a 2 kHz camera (every 5th row of the 0.1 ms trajectory): z1 and z2 with Gaussian
/// noise of sigma (m, seeded) on a clock `offset` (s) ahead of the simulation's.
MeasuredTrajectory synthetic_trajectory(double sigma, double offset) {
  const RunResult run = simulate(load_scene(gg3462(), {{"contact.delta_ss", "0.024"}, {"measure.bounces", "\"all\""}}), false,
                                 Recording::kinematics);
  const auto col = [&](const char* name) {
    return static_cast<std::size_t>(std::find(run.columns.begin(), run.columns.end(), name) - run.columns.begin());
  };
  std::mt19937 rng(3462);
  std::normal_distribution<double> noise(0.0, sigma);
  MeasuredTrajectory m;
  m.path = "synthetic.csv";
  m.columns = {"z1", "z2"};
  m.z.resize(2);
  for (std::size_t k = 0; k < run.rows.size(); k += 5) {
    m.t.push_back(run.rows[k][0] + offset);
    m.z[0].push_back(run.rows[k][col("z1")] + noise(rng));
    m.z[1].push_back(run.rows[k][col("z2")] + noise(rng));
    m.lines.push_back(static_cast<int>(m.t.size()) + 1);
  }
  return m;
}

struct Timed {
  SearchResult r;
  double wall_s;
};

Timed fit_delta_ss(const MeasuredTrajectory& m, const SearchOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string scene = gg3462();
  const std::vector<Override> base{{"contact.delta_ss", "0.006"}};  // the distant start
  const Scene sc = load_scene(scene, base);
  const std::vector<FitParameter> params{parse_fit_parameter("contact.delta_ss=0.005:0.05", scene, base)};
  const TrajectoryWindow w = trajectory_window(m, sc, std::nullopt, std::nullopt, std::nullopt);
  auto evaluate = [&](const std::vector<double>& v) {
    std::vector<Override> ov = base;
    for (const auto& o : overrides_for(params, v)) ov.push_back(o);
    return evaluate_trajectory(m, w, scene, ov);
  };
  SearchOptions o = opt;
  o.inner_parameters = 1;  // the time offset
  SearchResult r = search(params, {sc.contact.delta_ss}, evaluate, o, test::thread_runner(2));
  return {std::move(r), std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
}

void report(const char* what, const Timed& t) {
  std::cout << what << ": delta_ss = " << t.r.best[0] << ", rms = " << t.r.best_eval.rms * 1e6 << " um, tau = "
            << t.r.best_eval.tau.value_or(NAN) * 1e3 << " ms, " << t.r.evaluations.size() << " evaluations, " << t.wall_s
            << " s on 2 threads";
  if (!t.r.profiles.empty())
    std::cout << ", profile interval [" << t.r.profiles[0].lo.value_or(NAN) << ", " << t.r.profiles[0].hi.value_or(NAN) << "]";
  std::cout << "\n";
}

}  // namespace

// How well a trajectory tells delta_ss: on gg3462 the spheres' paths away from the contact hardly depend on it (a
// larger delta_ss starts the contact earlier but with a smaller e, and the two nearly cancel): the trajectory at
// delta_ss = 0.005 differs from the one at 0.024 by 0.25 µm rms over the default window, at 0.022 by 0.036 µm. The
// least-squares standard error of delta_ss from N = 240 residuals (2 kHz, z1 and z2) of noise sigma is about
// sigma / (sqrt(N) * 18 µm) = 0.00036 at sigma = 0.1 µm: the bound 0.002 is about 5.6 standard errors; the default
// profile interval (95 % confidence, about 1.96 standard errors either side) must hold 0.024.
constexpr double kTrajectoryNoise = 0.1e-6;  // m
constexpr double kClockOffset = 0.0017;       // s, the measurement's clock ahead of the simulation's

void expect_recovered(const SearchResult& r) {
  ASSERT_EQ(r.best.size(), 1u);
  EXPECT_NEAR(r.best[0], 0.024, 0.002);
  ASSERT_EQ(r.profiles.size(), 1u);
  EXPECT_FALSE(r.rule.given);
  EXPECT_EQ(r.rule.confidence, 0.95);
  EXPECT_EQ(r.rule.p, 2u);  // delta_ss and the time offset
  EXPECT_EQ(r.rule.n, r.best_eval.residuals);
  ASSERT_TRUE(r.profiles[0].lo && r.profiles[0].hi);  // the measurement determines delta_ss at 0.1 um of noise
  EXPECT_LT(*r.profiles[0].lo, 0.024);
  EXPECT_GT(*r.profiles[0].hi, 0.024);
  ASSERT_TRUE(r.best_eval.tau);
  EXPECT_NEAR(*r.best_eval.tau, kClockOffset, 1e-5);
}

TEST(CalibrateRecovery, DeltaSsFromANoisyTrajectoryWithScan) {
  const MeasuredTrajectory m = synthetic_trajectory(kTrajectoryNoise, kClockOffset);
  SearchOptions opt;
  const Timed t = fit_delta_ss(m, opt);
  report("scan + local + profile", t);
  expect_recovered(t.r);
}

TEST(CalibrateRecovery, DeltaSsFromANoisyTrajectoryLocalOnly) {
  const MeasuredTrajectory m = synthetic_trajectory(kTrajectoryNoise, kClockOffset);
  SearchOptions opt;
  opt.scan = 0;
  const Timed t = fit_delta_ss(m, opt);
  report("local only + profile", t);
  expect_recovered(t.r);
}

// A camera's 20 µm of noise is 80 times the whole effect of delta_ss on the window: the calibration must say that it
// cannot tell, its profile staying within the 95 % confidence factor over the whole range.
TEST(CalibrateRecovery, DeltaSsUndeterminedUnderCameraNoise) {
  const MeasuredTrajectory m = synthetic_trajectory(20e-6, kClockOffset);
  SearchOptions opt;
  const Timed t = fit_delta_ss(m, opt);
  report("20 um noise", t);
  ASSERT_EQ(t.r.profiles.size(), 1u);
  EXPECT_FALSE(t.r.profiles[0].lo);
  EXPECT_FALSE(t.r.profiles[0].hi);
  EXPECT_NEAR(t.r.best_eval.rms, 20e-6, 2e-6);  // the noise, not a misfit
}
namespace {

/// An e table of gg3462 made at (delta_ss, e_dry) = (0.024, 0.95) over 7 impact speeds 0.08-0.8 m/s (St ~ 70-710),
/// with Gaussian noise of sigma_e (seeded). e_dry scales e nearly alike at every speed; delta_ss lowers it by 0.035
/// at 0.08 m/s and by 0.009 at 0.8 m/s per 0.02: the two are told apart by that slope only (their estimates
/// correlate at 0.91).
MeasuredTable synthetic_table(double sigma_e) {
  MeasuredTable t;
  t.path = "table.csv";
  t.keys = {"sphere[0].velocity"};
  std::mt19937 rng(24);
  std::normal_distribution<double> noise(0.0, sigma_e);
  const std::vector<Override> truth{{"contact.delta_ss", "0.024"}, {"contact.e_dry", "0.95"}};
  for (int i = 0; i < 7; ++i) {
    const double v = 0.08 * std::pow(10.0, i / 6.0);
    std::vector<Override> ov = truth;
    ov.push_back({"sphere[0].velocity", std::to_string(v)});
    const RunSummary s = simulate_for_e(load_scene(gg3462(), ov)).summary;
    t.values.push_back({std::stod(std::to_string(v))});
    t.e.push_back(std::clamp(s.e.value() + noise(rng), 0.0, 1.0));
    t.lines.push_back(i + 2);
  }
  return t;
}

}  // namespace

TEST(CalibrateRecovery, DeltaSsAndEDryFromANoisyETable) {
  const auto t0 = std::chrono::steady_clock::now();
  // Linearised least squares at the truth (finite differences of e over the rows) gives standard errors of
  // 0.0017 in delta_ss and 0.0018 in e_dry at sigma_e = 0.002: the bounds below are 3 of them.
  const MeasuredTable m = synthetic_table(0.002);
  const std::string scene = gg3462();
  const std::vector<Override> base{{"contact.delta_ss", "0.006"}, {"contact.e_dry", "0.85"}};  // a distant start
  const Scene sc = load_scene(scene, base);
  check_table_keys(m, scene, base);
  const std::vector<FitParameter> params{parse_fit_parameter("contact.delta_ss=0.005:0.05", scene, base),
                                         parse_fit_parameter("contact.e_dry=0.8:1", scene, base)};
  auto evaluate = [&](const std::vector<double>& v) {
    std::vector<Override> ov = base;
    for (const auto& o : overrides_for(params, v)) ov.push_back(o);
    return evaluate_table(m, scene, ov);
  };
  SearchOptions opt;
  opt.profile_points = 9;
  const SearchResult r = search(params, {sc.contact.delta_ss, sc.contact.e_dry}, evaluate, opt, test::thread_runner(2));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(r.best.size(), 2u);
  std::cout << "e table: delta_ss = " << r.best[0] << ", e_dry = " << r.best[1] << ", rms = " << r.best_eval.rms << ", "
            << r.evaluations.size() << " evaluations, " << wall << " s on 2 threads\n";
  EXPECT_NEAR(r.best[0], 0.024, 0.005);
  EXPECT_NEAR(r.best[1], 0.95, 0.0055);
  EXPECT_EQ(r.failed, 0);
  // The default interval (95 % confidence, n = 7 rows, p = 2) of each holds the truth.
  EXPECT_EQ(r.rule.n, 7u);
  EXPECT_EQ(r.rule.p, 2u);
  ASSERT_EQ(r.profiles.size(), 2u);
  const double truth[] = {0.024, 0.95};
  for (std::size_t k = 0; k < 2; ++k) {
    std::cout << "  interval " << k << ": [" << r.profiles[k].lo.value_or(NAN) << ", " << r.profiles[k].hi.value_or(NAN) << "]\n";
    ASSERT_TRUE(r.profiles[k].lo && r.profiles[k].hi) << k;  // seven rows determine both
    EXPECT_LT(*r.profiles[k].lo, truth[k]) << k;
    EXPECT_GT(*r.profiles[k].hi, truth[k]) << k;
  }
}
