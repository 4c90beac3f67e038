// SPDX-License-Identifier: BSD-3-Clause
// The calibration engine's identities: the parameter map and its overrides, the trajectory objective on a run's own
// trajectory (shifted or not), the default window, profile intervals, evaluations as bytes, a deterministic search,
// the confidence factor, and refined interval ends against the exact ones of a quadratic objective.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>

#include "calibrate/confidence.hpp"
#include "calibrate/evaluation_bytes.hpp"
#include "calibrate/fit_parameter.hpp"
#include "calibrate/objective.hpp"
#include "calibrate/profile.hpp"
#include "calibrate/search.hpp"
#include "core/materials.hpp"
#include "tests/calibrate_runner.hpp"

using namespace imcol;
using namespace imcol::calib;
using imcol::test::gg3462;

namespace {

/// A run's z1 and z2 as a measured trajectory, its clock shifted by `shift` (s).
MeasuredTrajectory as_measurement(const RunResult& run, double shift) {
  MeasuredTrajectory m;
  m.path = "run";
  m.columns = {"z1", "z2"};
  m.z.resize(2);
  const auto col = [&](const char* name) {
    return static_cast<std::size_t>(std::find(run.columns.begin(), run.columns.end(), name) - run.columns.begin());
  };
  const std::size_t c1 = col("z1"), c2 = col("z2");
  int line = 2;
  for (const auto& row : run.rows) {
    m.t.push_back(row[0] + shift);
    m.z[0].push_back(row[c1]);
    m.z[1].push_back(row[c2]);
    m.lines.push_back(line++);
  }
  return m;
}

/// gg3462 followed through t_end = 0.06 s (every bounce: the run is not cut after the first rebound).
const RunResult& gg3462_run() {
  static const RunResult run = simulate(load_scene(gg3462(), {{"measure.bounces", "\"all\""}}), false, Recording::kinematics);
  return run;
}

}  // namespace

TEST(CalibrateFormulas, ValueOfAndUnitOfRoundTripLinear) {
  const FitParameter p{"contact.delta_ss", 0.005, 0.05, Scale::linear};
  EXPECT_EQ(value_of(p, 0), 0.005);
  EXPECT_EQ(value_of(p, 1), 0.05);
  EXPECT_NEAR(value_of(p, 0.5), 0.0275, 1e-16);
  for (int i = 0; i <= 20; ++i) {
    const double u = i / 20.0;
    EXPECT_NEAR(unit_of(p, value_of(p, u)), u, 1e-14) << u;
  }
  EXPECT_EQ(unit_of(p, 0.001), 0.0);  // clamped
  EXPECT_EQ(unit_of(p, 1.0), 1.0);
}

TEST(CalibrateFormulas, ValueOfAndUnitOfRoundTripLog) {
  const FitParameter p{"fluid.viscosity", 1e-3, 1e-1, Scale::log};
  EXPECT_EQ(value_of(p, 0), 1e-3);
  EXPECT_EQ(value_of(p, 1), 1e-1);
  EXPECT_NEAR(value_of(p, 0.5), 1e-2, 1e-16);  // the geometric mean
  for (int i = 0; i <= 20; ++i) {
    const double u = i / 20.0;
    EXPECT_NEAR(unit_of(p, value_of(p, u)), u, 1e-14) << u;
  }
  EXPECT_EQ(unit_of(p, -1.0), 0.0);
}

TEST(CalibrateFormulas, OverridesReadBackToTheSameDouble) {
  const std::vector<FitParameter> params{{"contact.delta_ss", 0.005, 0.05, Scale::linear},
                                         {"sphere[0].velocity", 0.01, 1, Scale::log},
                                         {"fluid.viscosity", 1e-3, 1e-1, Scale::log}};
  for (const std::vector<double>& v : {std::vector<double>{0.1 / 3, 0.11 + 1e-16 * 3, 4e-3 / 7},
                                       std::vector<double>{0.024, 0.5, 0.002},
                                       std::vector<double>{std::nextafter(0.024, 1.0), 1.0 / 9, 0.0040000000000000001}}) {
    const auto ov = overrides_for(params, v);
    ASSERT_EQ(ov.size(), 3u);
    EXPECT_EQ(ov[0].key, "contact.delta_ss");
    const Scene sc = load_scene(gg3462(), ov);
    EXPECT_EQ(sc.contact.delta_ss, v[0]);
    EXPECT_EQ(sc.spheres[0].velocity, v[1]);
    EXPECT_EQ(sc.fluid->viscosity, v[2]);
  }
  // A whole number is written as a float (TOML would read "1" as an integer).
  EXPECT_EQ(overrides_for({{"sphere[0].velocity", 0.5, 2, Scale::linear}}, {1.0})[0].value, "1.0");
}

TEST(CalibrateFormulas, TrajectoryObjectiveOfARunAgainstItselfIsZeroAtZeroOffset) {
  const RunResult& run = gg3462_run();
  const MeasuredTrajectory m = as_measurement(run, 0);
  const Scene sc = load_scene(gg3462());
  const TrajectoryWindow w = trajectory_window(m, sc, std::nullopt, std::nullopt, std::nullopt);
  const Evaluation ev = trajectory_objective(m, w, run);
  ASSERT_TRUE(ev.ok) << ev.message;
  EXPECT_EQ(ev.objective, 0.0);
  ASSERT_TRUE(ev.tau);
  EXPECT_EQ(*ev.tau, 0.0);
}

TEST(CalibrateFormulas, TrajectoryObjectiveRecoversAClockOffsetOf3ms) {
  const RunResult& run = gg3462_run();
  const MeasuredTrajectory m = as_measurement(run, 0.003);  // the measurement's clock 3 ms ahead
  const Scene sc = load_scene(gg3462());
  const TrajectoryWindow w = trajectory_window(m, sc, std::nullopt, std::nullopt, std::nullopt);
  const Evaluation ev = trajectory_objective(m, w, run);
  ASSERT_TRUE(ev.ok) << ev.message;
  ASSERT_TRUE(ev.tau);
  // The golden-section search ends on a bracket of 1e-9 tau_max (~6e-11 s); the rows' times carry rounding.
  EXPECT_NEAR(*ev.tau, 0.003, 1e-8);
  EXPECT_LT(ev.rms, 1e-9);  // m: 1 nm, against 20 µm of noise in the recovery tests
}

TEST(CalibrateFormulas, TrajectoryWindowDefaultsOnGg3462) {
  const RunResult& run = gg3462_run();
  const MeasuredTrajectory m = as_measurement(run, 0);
  const Scene sc = load_scene(gg3462());
  const TrajectoryWindow w = trajectory_window(m, sc, std::nullopt, std::nullopt, std::nullopt);
  // Contact: the smallest gap z2 - z1 - D of the record (the run's gap column).
  const auto gap_col = static_cast<std::size_t>(std::find(run.columns.begin(), run.columns.end(), "gap") - run.columns.begin());
  std::size_t kmin = 0;
  for (std::size_t k = 0; k < run.rows.size(); ++k)
    if (run.rows[k][gap_col] < run.rows[kmin][gap_col]) kmin = k;
  EXPECT_NEAR(w.t_contact, run.rows[kmin][0], 1e-12);
  EXPECT_GT(w.t_contact, 0.02);
  EXPECT_LT(w.t_contact, 0.04);
  // One diameter at the approach speed: T = 0.0127 m / 0.110 m/s = 0.11545 s; before = -T and after = 2T are
  // clipped to the record [0, 0.06] s; tau_max = T / 2.
  const double T = 0.0127 / 0.110;
  EXPECT_NEAR(w.before, -w.t_contact, 1e-15);
  EXPECT_NEAR(w.after, m.t.back() - w.t_contact, 1e-15);
  EXPECT_NEAR(w.tau_max, T / 2, 1e-15);
  // Given values replace the defaults.
  const TrajectoryWindow g = trajectory_window(m, sc, -0.005, 0.01, 0.002);
  EXPECT_EQ(g.before, -0.005);
  EXPECT_EQ(g.after, 0.01);
  EXPECT_EQ(g.tau_max, 0.002);
}

TEST(CalibrateFormulas, ProfileIntervalInterpolatesWhereTheProfileCrossesTheThreshold) {
  // f = (u - 0.5)^2 + 0.01 on a grid of 0.1: threshold 0.02 is crossed at u = 0.4 and 0.6 exactly (grid points),
  // threshold 0.025 between 0.3 (0.05) and 0.4 (0.02): 0.4 - 0.1 * 0.005 / 0.03.
  std::vector<double> u, f;
  for (int i = 0; i <= 10; ++i) u.push_back(i / 10.0), f.push_back((u.back() - 0.5) * (u.back() - 0.5) + 0.01);
  auto [lo, hi] = profile_interval(u, f, 0.025);
  ASSERT_TRUE(lo && hi);
  EXPECT_NEAR(*lo, 0.4 - 0.1 * 0.005 / 0.03, 1e-12);
  EXPECT_NEAR(*hi, 0.6 + 0.1 * 0.005 / 0.03, 1e-12);
  // Within the threshold up to a bound (f <= 0.26 everywhere): no end on that side.
  std::tie(lo, hi) = profile_interval(u, f, 0.3);
  EXPECT_FALSE(lo);
  EXPECT_FALSE(hi);
  f[0] = 1;  // only the lower end rises above 0.3: between u = 0.1 (0.17) and 0 (1)
  std::tie(lo, hi) = profile_interval(u, f, 0.3);
  ASSERT_TRUE(lo);
  EXPECT_NEAR(*lo, 0.1 - 0.1 * (0.3 - 0.17) / (1 - 0.17), 1e-12);
  EXPECT_FALSE(hi);
}

TEST(CalibrateFormulas, EvaluationsTravelAsBytesUnchanged) {
  Evaluation a;
  a.ok = true;
  a.objective = 1.0 / 3;
  a.rms = std::sqrt(a.objective);
  a.tau = -2.5e-3 / 7;
  a.e_sim = {0.8, std::numeric_limits<double>::quiet_NaN(), 0.1 / 3};
  a.wall_s = 0.0123;
  a.residuals = 1402;
  Evaluation b;
  b.objective = std::numeric_limits<double>::infinity();
  b.rms = b.objective;
  b.message = "solver failed: \"CV_TOO_MUCH_WORK\"\n";
  const auto back = evaluations_from_bytes(evaluations_to_bytes({{{0.024, 1.0 / 7}, a}, {{0.03}, b}}));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].first, (std::vector<double>{0.024, 1.0 / 7}));
  EXPECT_TRUE(back[0].second.ok);
  EXPECT_EQ(back[0].second.objective, a.objective);
  EXPECT_EQ(back[0].second.rms, a.rms);
  EXPECT_EQ(*back[0].second.tau, *a.tau);
  ASSERT_EQ(back[0].second.e_sim.size(), 3u);
  EXPECT_EQ(back[0].second.e_sim[0], 0.8);
  EXPECT_TRUE(std::isnan(back[0].second.e_sim[1]));
  EXPECT_EQ(back[0].second.e_sim[2], 0.1 / 3);
  EXPECT_EQ(back[0].second.wall_s, 0.0123);
  EXPECT_EQ(back[0].second.residuals, 1402u);
  EXPECT_FALSE(back[1].second.ok);
  EXPECT_TRUE(std::isinf(back[1].second.objective));
  EXPECT_FALSE(back[1].second.tau);
  EXPECT_EQ(back[1].second.message, b.message);
}

TEST(CalibrateFormulas, SearchIsDeterministicAndFindsAQuadraticsMinimum) {
  // A cheap objective with its minimum at (0.3, 20) on a linear and a log axis; one value fails.
  const std::vector<FitParameter> params{{"a", 0, 1, Scale::linear}, {"b", 1, 100, Scale::log}};
  auto evaluate = [](const std::vector<double>& v) {
    Evaluation ev;
    ev.ok = v[0] < 0.95;  // the right edge fails
    const double db = std::log10(v[1] / 20);
    ev.objective = ev.ok ? (v[0] - 0.3) * (v[0] - 0.3) + db * db + 1e-4 : std::numeric_limits<double>::infinity();
    ev.rms = std::sqrt(ev.objective);
    return ev;
  };
  SearchOptions opt;
  opt.profile_points = 9;
  opt.factor = 2;
  opt.refine = 4;
  opt.refine_to = 0;  // every round refines every end: a count known in advance
  std::size_t progress_calls = 0, last_evaluations = 0;
  const Progress progress = [&](Stage, std::size_t done, std::size_t items, std::size_t evaluations, double) {
    ++progress_calls;
    EXPECT_LE(done, items);
    EXPECT_GE(evaluations, last_evaluations);
    last_evaluations = evaluations;
  };
  const SearchResult serial = search(params, {0.9, 2}, evaluate, opt, test::thread_runner(1), progress);
  // One progress line per work item: the start, 17 scan points, 2 local searches, 2 x 9 profile points, 4 rounds of
  // the 4 interval ends.
  EXPECT_EQ(progress_calls, 1u + 17 + 2 + 18 + 16);
  EXPECT_EQ(last_evaluations, serial.evaluations.size());
  // Items finishing in another order (threads, or ranks handing in last item first), and the stage inputs passing
  // through share: the same evaluations, in the same order.
  calib::Runner reversed = test::thread_runner(1);
  int shares = 0;
  reversed.run = [](std::size_t n, const std::function<std::string(std::size_t)>& work,
                    const std::function<void(std::size_t, std::string, int)>& done) {
    for (std::size_t i = n; i-- > 0;) done(i, work(i), static_cast<int>(i % 3));
  };
  reversed.share = [&](std::string&) { ++shares; };
  for (const calib::Runner& runner : {test::thread_runner(2), reversed}) {
    const SearchResult other = search(params, {0.9, 2}, evaluate, opt, runner);
    ASSERT_EQ(serial.evaluations.size(), other.evaluations.size());
    for (std::size_t i = 0; i < serial.evaluations.size(); ++i) {
      EXPECT_EQ(serial.evaluations[i].stage, other.evaluations[i].stage) << i;
      EXPECT_EQ(serial.evaluations[i].item, other.evaluations[i].item) << i;
      EXPECT_EQ(serial.evaluations[i].values, other.evaluations[i].values) << i;
    }
    EXPECT_EQ(serial.best, other.best);
  }
  EXPECT_EQ(shares, 2 + 4);  // the local searches' starts, the profiles' best point, each edge round's points
  ASSERT_EQ(serial.best.size(), 2u);
  EXPECT_NEAR(serial.best[0], 0.3, 0.01);
  EXPECT_NEAR(std::log10(serial.best[1] / 20), 0, 0.01);
  EXPECT_LT(serial.best_eval.objective, 1.01e-4);
  EXPECT_EQ(serial.evaluations.front().stage, Stage::start);
  EXPECT_EQ(serial.evaluations.front().values, (std::vector<double>{0.9, 2}));
  // Profiles: objective <= 2 x best, i.e. (a - 0.3)^2 <= 1e-4 (b re-optimised): a in [0.29, 0.31] up to the
  // interpolation on a grid of 1/8 with the best inserted.
  ASSERT_EQ(serial.profiles.size(), 2u);
  const Profile& pa = serial.profiles[0];
  ASSERT_TRUE(pa.lo && pa.hi);
  EXPECT_LT(*pa.lo, 0.3);
  EXPECT_GT(*pa.lo, 0.28);
  EXPECT_GT(*pa.hi, 0.3);
  EXPECT_LT(*pa.hi, 0.32);
  EXPECT_GT(serial.failed, 0);  // the scan's points with a >= 0.95
}

TEST(CalibrateFormulas, ChiSquareQuantileAndConfidenceFactor) {
  EXPECT_NEAR(chi2_1_quantile(0.95), 3.841459, 1e-6);
  EXPECT_NEAR(chi2_1_quantile(0.6827), 1.0, 1e-3);  // one standard deviation: P(|Z| < 1) = 0.682689
  EXPECT_NEAR(chi2_1_quantile(0.99), 6.634897, 1e-6);
  for (double y : {-0.9, -0.3, 0.1, 0.5, 0.999}) EXPECT_NEAR(std::erf(erf_inverse(y)), y, 1e-15) << y;
  EXPECT_NEAR(confidence_factor(0.95, 1402, 2), 1 + 3.841459 / 1400, 1e-9);
  EXPECT_TRUE(std::isinf(confidence_factor(0.95, 2, 2)));  // no residual left to estimate the noise
}

namespace {

/// A least-squares objective of known shape, no simulation: J = J0 (1 + (x - x0)' A (x - x0)) over n residuals.
struct Quadratic {
  std::vector<double> x0;
  std::vector<std::vector<double>> a;
  double j0 = 1e-6;
  std::size_t n = 40;
  Evaluation operator()(const std::vector<double>& v) const {
    double q = 0;
    for (std::size_t i = 0; i < v.size(); ++i)
      for (std::size_t k = 0; k < v.size(); ++k) q += (v[i] - x0[i]) * a[i][k] * (v[k] - x0[k]);
    Evaluation ev;
    ev.ok = true;
    ev.objective = j0 * (1 + q);
    ev.rms = std::sqrt(ev.objective);
    ev.residuals = n;
    return ev;
  }
};

/// The profile of J along x_j (the other minimised) is J0 (1 + c (x_j - x0_j)^2), c = 1 / (A^-1)_jj; its interval
/// within factor × best: x0_j ± sqrt((threshold / J0 - 1) / c).
std::pair<double, double> exact_interval(const Quadratic& f, std::size_t j, double threshold) {
  double c = f.a[0][0];
  if (f.a.size() == 2) {
    const double det = f.a[0][0] * f.a[1][1] - f.a[0][1] * f.a[1][0];
    c = det / f.a[1 - j][1 - j];
  }
  const double h = std::sqrt((threshold / f.j0 - 1) / c);
  return {f.x0[j] - h, f.x0[j] + h};
}

}  // namespace

// The refined ends against the exact interval: 15 profile points on [0, 1] are 1/14 = 0.071 apart; bisection until a
// bracket is 1/64 of the interval (0.3 wide here) takes 4 rounds or 5 (the width is known from the inside points) and
// leaves a bracket h of 0.0045 or less, and a line through a parabola's two points of that bracket crosses the threshold
// within h^2 / (8 w) of its crossing (w the interval's half-width, 0.15): 1.7e-5. The ends must be within 5e-5, 1400
// times finer than the profile's spacing; without the refinement they are not.
TEST(CalibrateFormulas, RefinedIntervalMatchesTheExactOneInOneParameter) {
  Quadratic f;
  f.x0 = {0.4137};
  f.n = 40;
  const double factor = confidence_factor(0.95, f.n, 1);
  f.a = {{(factor - 1) / (0.15 * 0.15)}};  // the interval's half-width about 0.15
  const std::vector<FitParameter> params{{"x", 0, 1, Scale::linear}};
  SearchOptions opt;  // the defaults: 95 % confidence, 15 profile points, brackets to 1/64 of the interval
  const SearchResult r = search(params, {0.9}, f, opt, test::thread_runner(2));
  ASSERT_EQ(r.profiles.size(), 1u);
  EXPECT_FALSE(r.rule.given);
  EXPECT_EQ(r.rule.n, 40u);
  EXPECT_EQ(r.rule.p, 1u);
  EXPECT_NEAR(r.rule.factor, factor, 1e-15);
  EXPECT_EQ(r.rule.threshold, r.rule.factor * r.best_eval.objective);
  const auto [lo, hi] = exact_interval(f, 0, r.rule.threshold);
  ASSERT_TRUE(r.profiles[0].lo && r.profiles[0].hi);
  EXPECT_NEAR(*r.profiles[0].lo, lo, 5e-5);
  EXPECT_NEAR(*r.profiles[0].hi, hi, 5e-5);
  std::cout << "d = 1: ends off the exact ones by " << *r.profiles[0].lo - lo << ", " << *r.profiles[0].hi - hi << "\n";
  // Refined points join the profile, sorted; 2 ends x 4 or 5 rounds, one evaluation each.
  const auto edge = std::count_if(r.evaluations.begin(), r.evaluations.end(), [](const auto& e) { return e.stage == Stage::edge; });
  EXPECT_GE(edge, 8);
  EXPECT_LE(edge, 10);
  EXPECT_TRUE(r.profiles[0].resolved);
  EXPECT_EQ(r.profiles[0].values.size(), 15u + 1 + static_cast<std::size_t>(edge));
  EXPECT_TRUE(std::is_sorted(r.profiles[0].values.begin(), r.profiles[0].values.end()));
  // Without refinement the linear interpolation between profile points misses by far more.
  opt.refine = 0;
  const SearchResult coarse = search(params, {0.9}, f, opt, test::thread_runner(2));
  ASSERT_TRUE(coarse.profiles[0].lo && coarse.profiles[0].hi);
  std::cout << "d = 1 unrefined: off by " << *coarse.profiles[0].lo - lo << ", " << *coarse.profiles[0].hi - hi << "\n";
  EXPECT_GT(std::max(std::abs(*coarse.profiles[0].lo - lo), std::abs(*coarse.profiles[0].hi - hi)), 10 * 5e-5);
}

// A narrow interval (0.004 wide, 18 times narrower than the profile's spacing) is refined until its brackets are 1/64
// of it: 6.3e-5 or less, so that the line through a bracket misses the crossing by h^2 / (8 w) < 2.5e-7; the ends must
// lie within 1e-6. With at most 4 rounds the brackets stay 0.0045 wide and the profile says its ends are not resolved.
TEST(CalibrateFormulas, ANarrowIntervalIsRefinedUntilItsEndsAreResolved) {
  Quadratic f;
  f.x0 = {0.4137};
  f.n = 40;
  const double factor = confidence_factor(0.95, f.n, 1);
  f.a = {{(factor - 1) / (0.002 * 0.002)}};  // half-width 0.002
  const std::vector<FitParameter> params{{"x", 0, 1, Scale::linear}};
  SearchOptions opt;
  const SearchResult r = search(params, {0.9}, f, opt, test::thread_runner(2));
  const auto [lo, hi] = exact_interval(f, 0, r.rule.threshold);
  ASSERT_TRUE(r.profiles[0].lo && r.profiles[0].hi);
  EXPECT_NEAR(*r.profiles[0].lo, lo, 1e-6);
  EXPECT_NEAR(*r.profiles[0].hi, hi, 1e-6);
  EXPECT_TRUE(r.profiles[0].resolved);
  const auto edge = std::count_if(r.evaluations.begin(), r.evaluations.end(), [](const auto& e) { return e.stage == Stage::edge; });
  std::cout << "narrow interval: " << edge << " edge evaluations, ends off by " << *r.profiles[0].lo - lo << ", "
            << *r.profiles[0].hi - hi << "\n";
  EXPECT_LE(edge, 2 * opt.refine);
  opt.refine = 4;
  const SearchResult few = search(params, {0.9}, f, opt, test::thread_runner(2));
  EXPECT_FALSE(few.profiles[0].resolved);
}

// An edge point that improves the best lowers the threshold, so the interval's ends move: the brackets follow them.
// A dip (J0 / 2, 1e-9 wide) at the first edge point, which no evaluation before the edges meets: the interval shrinks
// about it. An interval said to be resolved has, about each finite end, neighbouring profile points at most refine_to
// of the interval's width apart.
TEST(CalibrateFormulas, TheBracketsFollowABestFoundAtAnEdge) {
  Quadratic q;
  q.x0 = {0.4137};
  q.n = 40;
  q.a = {{(confidence_factor(0.95, q.n, 1) - 1) / (0.15 * 0.15)}};
  const std::vector<FitParameter> params{{"x", 0, 1, Scale::linear}};
  const SearchOptions opt;
  const SearchResult plain = search(params, {0.9}, q, opt, test::thread_runner(1));
  const auto first_edge = std::find_if(plain.evaluations.begin(), plain.evaluations.end(), [](const auto& e) { return e.stage == Stage::edge; });
  ASSERT_NE(first_edge, plain.evaluations.end());
  const double dip = first_edge->values[0];
  const double kWidth = 1e-9;
  for (auto e = plain.evaluations.begin(); e != first_edge; ++e) ASSERT_GT(std::abs(e->values[0] - dip), kWidth);
  auto dipped = [&](const std::vector<double>& v) {
    Evaluation ev = q(v);
    if (std::abs(v[0] - dip) <= kWidth) ev.objective = q.j0 / 2, ev.rms = std::sqrt(ev.objective);
    return ev;
  };
  const SearchResult r = search(params, {0.9}, dipped, opt, test::thread_runner(1));
  ASSERT_EQ(r.best.size(), 1u);
  EXPECT_EQ(r.best_eval.objective, q.j0 / 2);
  EXPECT_EQ(r.rule.threshold, r.rule.factor * q.j0 / 2);
  ASSERT_EQ(r.profiles.size(), 1u);
  const Profile& p = r.profiles[0];
  ASSERT_TRUE(p.lo && p.hi);
  EXPECT_LE(*p.lo, dip);
  EXPECT_GE(*p.hi, dip);
  EXPECT_LT(*p.hi - *p.lo, 0.01);  // about the dip alone: the parabola's floor lies above the lowered threshold
  if (p.resolved)
    for (const double end : {*p.lo, *p.hi}) {
      const auto above = std::upper_bound(p.values.begin(), p.values.end(), end);
      ASSERT_TRUE(above != p.values.begin() && above != p.values.end()) << end;
      EXPECT_LE(*above - *(above - 1), opt.refine_to * (*p.hi - *p.lo)) << "the profile points about the end " << end;
    }
}

// Two correlated parameters: each profile point and refined end re-optimises the other (a short local search), so
// the profile lies a little above the exact one where that search stops (xtol 1e-3 in u: about b (1e-3)^2 in J/J0,
// 4e-6, a shift of 4e-6 / (2 c w) ~ 3e-6 in the end); with the bisection's 1.7e-5 the ends must lie within 1e-4 of
// the exact ones, 700 times finer than the spacing.
TEST(CalibrateFormulas, RefinedIntervalMatchesTheExactOneInTwoParameters) {
  Quadratic f;
  f.x0 = {0.4137, 0.5821};
  f.n = 60;
  const double factor = confidence_factor(0.95, f.n, 2);
  const double c = (factor - 1) / (0.15 * 0.15);  // profile curvature of x: half-width 0.15
  f.a = {{c + 1.0, 2.0}, {2.0, 4.0}};             // c = a00 - a01^2 / a11
  const std::vector<FitParameter> params{{"x", 0, 1, Scale::linear}, {"y", 0, 1, Scale::linear}};
  const SearchResult r = search(params, {0.9, 0.1}, f, SearchOptions{}, test::thread_runner(2));
  ASSERT_EQ(r.profiles.size(), 2u);
  EXPECT_EQ(r.rule.p, 2u);
  EXPECT_NEAR(r.rule.factor, factor, 1e-15);
  for (std::size_t j = 0; j < 2; ++j) {
    const auto [lo, hi] = exact_interval(f, j, r.rule.threshold);
    ASSERT_TRUE(r.profiles[j].lo && r.profiles[j].hi) << j;
    EXPECT_NEAR(*r.profiles[j].lo, lo, 1e-4) << j;
    EXPECT_NEAR(*r.profiles[j].hi, hi, 1e-4) << j;
    std::cout << "d = 2, parameter " << j << ": ends off the exact ones by " << *r.profiles[j].lo - lo << ", " << *r.profiles[j].hi - hi
              << "\n";
  }
  EXPECT_GT(std::count_if(r.evaluations.begin(), r.evaluations.end(), [](const auto& e) { return e.stage == Stage::edge; }), 8);
}
