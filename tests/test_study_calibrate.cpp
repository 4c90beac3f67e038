// SPDX-License-Identifier: BSD-3-Clause
// The calibration study (study/calibrate.hpp) on threads: progress after every evaluation, its total the search's
// budget and a last call with everything done; cancelled after k evaluations, it returns those k with the best
// among them and no intervals; a cancelled search runs no further evaluation.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/materials.hpp"
#include "study/calibrate.hpp"

namespace {

using imcol::study::CalibrationInputs;

/// gg3462's trajectory fitted in contact.delta_ss with a few evaluations.
CalibrationInputs quick_fit_inputs(int scan, int starts, int max_evals) {
  imcol::study::CalibrationOptions opt;
  opt.data = imcol::data_dir() + "/measurements/gg3462_trajectory.csv";
  opt.fits = {"contact.delta_ss=0.005:0.05"};
  opt.search.scan = scan;
  opt.search.starts = starts;
  opt.search.max_evals = max_evals;
  opt.search.profile_points = 0;
  return imcol::study::read_calibration_inputs(imcol::data_dir() + "/scenes/gg3462.toml", {}, opt);
}

}  // namespace

TEST(StudyCalibrate, ProgressAfterEachEvaluationThenDone) {
  const CalibrationInputs in = quick_fit_inputs(2, 1, 3);
  std::mutex mu;
  std::vector<std::pair<std::size_t, std::size_t>> calls;
  imcol::study::Hooks hooks;
  hooks.progress = [&](std::size_t done, std::size_t total) {
    std::lock_guard lock(mu);
    calls.emplace_back(done, total);
  };
  const auto r = imcol::study::run_calibration(in, imcol::study::threads(2), hooks);
  const std::size_t n = r.search.evaluations.size();
  EXPECT_FALSE(r.cancelled);
  EXPECT_TRUE(r.search.best_eval.ok);
  ASSERT_GE(n, 3u);  // the start and two scan points, then the local search's
  EXPECT_LE(n, imcol::study::evaluation_budget(1, in.search));
  ASSERT_EQ(calls.size(), n + 1);
  const std::size_t budget = imcol::study::evaluation_budget(1, in.search);
  EXPECT_EQ(budget, 3u + 3u);  // 2 scan points and the start, one local search of 3
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(calls[i].first, i + 1);
    EXPECT_EQ(calls[i].second, budget);
  }
  EXPECT_EQ(calls.back(), std::make_pair(n, n));
  EXPECT_TRUE(r.best_run.has_value());  // a trajectory's fitted run
}

TEST(StudyCalibrate, CancelledAfterKEvaluationsReturnsThoseK) {
  const CalibrationInputs in = quick_fit_inputs(6, 1, 10);
  constexpr std::size_t k = 3;
  std::atomic<std::size_t> done{0};
  imcol::study::Hooks hooks;
  hooks.progress = [&](std::size_t d, std::size_t) { done = d; };
  hooks.cancelled = [&] { return done.load() >= k; };
  const auto r = imcol::study::run_calibration(in, imcol::study::threads(1), hooks);
  EXPECT_TRUE(r.cancelled);
  ASSERT_EQ(r.search.evaluations.size(), k);
  EXPECT_EQ(done.load(), k);  // no evaluation after the cancel
  EXPECT_EQ(r.search.evaluations[0].stage, imcol::calib::Stage::start);
  double best = INFINITY;
  for (const auto& e : r.search.evaluations) {
    EXPECT_NE(e.stage, imcol::calib::Stage::local);
    if (e.eval.ok) best = std::min(best, e.eval.objective);
  }
  ASSERT_TRUE(r.search.best_eval.ok);
  EXPECT_EQ(r.search.best_eval.objective, best);
  EXPECT_TRUE(r.search.profiles.empty());
  EXPECT_FALSE(r.best_run.has_value());  // nothing more runs once cancelled
}

TEST(StudyCalibrate, CancelledBeforeTheStartRunsNothing) {
  const CalibrationInputs in = quick_fit_inputs(2, 1, 3);
  imcol::study::Hooks hooks;
  std::size_t calls = 0;
  hooks.progress = [&](std::size_t, std::size_t) { ++calls; };
  hooks.cancelled = [] { return true; };
  const auto r = imcol::study::run_calibration(in, imcol::study::threads(2), hooks);
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.search.evaluations.empty());
  EXPECT_FALSE(r.search.best_eval.ok);
  EXPECT_EQ(calls, 1u);  // the last call alone: nothing done
}
