// SPDX-License-Identifier: BSD-3-Clause
// The seam between the model's events and the rules in run/ (model/watcher.hpp): the model alone arms only its own
// roots; a watcher's root fires under its kind and name, and its stop time ends the run.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "core/scene.hpp"
#include "integrators/integrator.hpp"
#include "model/collision_model.hpp"
#include "run/event_kind.hpp"
#include "run/recorder.hpp"
#include "run/watch.hpp"

namespace {

using namespace imcol;

std::string scene_path(const std::string& name) { return std::string(IMCOL_DATA_DIR) + "/scenes/" + name; }

std::vector<std::string> root_names(const model::CollisionModel& m) {
  std::vector<std::string> names;
  for (const auto& r : m.roots()) names.push_back(r.name);
  return names;
}

TEST(Watchers, TheModelAloneArmsOnlyItsContactRootsAndTheWatchersFollowThem) {
  const Scene sc = load_scene(scene_path("default.toml"));
  model::CollisionModel model(sc);
  const auto alone = root_names(model);
  ASSERT_FALSE(alone.empty());
  EXPECT_EQ(alone.front(), "gap=delta_ss (in)");
  for (const auto& n : alone) EXPECT_EQ(n.find("instant"), std::string::npos) << n;
  run::Watch watch(model, sc);
  const auto watched = root_names(model);
  // The model's contact root, then the watchers' (stopped approach, instant gap), then the model's other roots.
  ASSERT_EQ(watched.size(), alone.size() + 2);
  EXPECT_EQ(watched[0], alone[0]);
  EXPECT_EQ(watched[1], "u_rel=stall_fraction*U_rel0 (approach stopped)");
  EXPECT_EQ(watched[2], "gap=instant_gap (in)");
  for (std::size_t i = 1; i < alone.size(); ++i) EXPECT_EQ(watched[i + 2], alone[i]);
}

/// Arms one inward crossing of half the initial gap and ends the run there.
class HalfGap : public model::EventWatcher {
 public:
  explicit HalfGap(double gap) : gap_(gap) {}
  void roots(std::vector<model::WatchedRoot>& out) const override {
    if (!t_) out.push_back({run::tag(run::EventKind::measure_out), "gap=half the initial gap (in)", model::WatchedRoot::Of::gap, gap_, -1, true});
  }
  std::optional<model::Declared> on_event(const model::EventRecord& e) override {
    if (run::kind_of(e) == run::EventKind::measure_out) t_ = e.t;
    return std::nullopt;
  }
  double stop_time() const override { return t_.value_or(std::numeric_limits<double>::infinity()); }
  std::optional<double> t_;
  double gap_;
};

TEST(Watchers, AWatchersRootFiresUnderItsKindAndNameAndItsStopTimeEndsTheRun) {
  const Scene sc = load_scene(scene_path("default.toml"));
  model::CollisionModel model(sc);
  HalfGap half(0.5 * model.initial_gap());
  model.watch(half);
  struct : Observer {
    void sample(double t, std::span<const double>, bool) override { last = t; }
    double last = -1;
  } obs;
  IntegratorSettings st;
  st.output_dt = sc.output.dt;
  integrate(model, st, obs);
  ASSERT_TRUE(half.t_);
  ASSERT_FALSE(model.events().empty());
  const auto& e = model.events().back();
  EXPECT_EQ(run::kind_of(e), run::EventKind::measure_out);
  EXPECT_EQ(e.name, "gap=half the initial gap (in)");
  EXPECT_NEAR(e.gap, 0.5 * model.initial_gap(), 1e-6 * model.initial_gap());
  EXPECT_EQ(model.stop_time(), *half.t_);
  EXPECT_EQ(obs.last, *half.t_);  // the run ended at the watcher's event, long before t_end
  EXPECT_LT(*half.t_, sc.solver.t_end);
  EXPECT_FALSE(model.t_contact());
}

// The progress line's time left (run/recorder.hpp, ProgressEstimate): from the rate of the last ProgressEstimate::kWindow
// s of wall time, and called an estimate. A run that slows down (gondret_st192 with contact.beta = 2e8: 2 s of wall
// time for its first 1.1 s, then 0.005 s of simulated time per wall second) must not keep the early rate.
TEST(Progress, TheTimeLeftFollowsTheRecentRateWhenTheRunSlowsDown) {
  run::ProgressEstimate est;
  EXPECT_FALSE(est.seconds_left(1.5));
  // 0.55 s of simulated time per wall second for 2 s, then 0.005 s per wall second.
  double t = 0;
  for (int k = 0; k <= 8; ++k) est.add(0.25 * k, t = 0.1375 * k);
  ASSERT_TRUE(est.seconds_left(1.5));
  EXPECT_NEAR(*est.seconds_left(1.5), (1.5 - 1.1) / 0.55, 1e-9);  // the rate so far
  for (int k = 1; k <= 40; ++k) est.add(2.0 + 0.25 * k, t = 1.1 + 0.00125 * k);
  // 10 s later the window holds only the slow rate: (1.5 − 1.15) / 0.005 = 70 s, where the whole run's average rate
  // (1.15 s in 12 s) would say 3.7 s.
  ASSERT_TRUE(est.seconds_left(1.5));
  EXPECT_NEAR(*est.seconds_left(1.5), (1.5 - t) / 0.005, 1e-6);
  // Halfway through the window after a change of rate, the estimate lies between the two rates' projections.
  run::ProgressEstimate mixed;
  for (int k = 0; k <= 40; ++k) mixed.add(0.25 * k, 0.025 * k);              // 0.1 s per wall second to 10 s
  for (int k = 1; k <= 6; ++k) mixed.add(10.0 + 0.25 * k, 1.0 + 0.0025 * k);  // then 0.01 s per wall second
  const double left = *mixed.seconds_left(2.0), t_now = 1.015;
  EXPECT_GT(left, (2.0 - t_now) / 0.1);
  EXPECT_LT(left, (2.0 - t_now) / 0.01);
  EXPECT_NEAR(left, (2.0 - t_now) * 3.0 / (1.015 - 0.85), 1e-9);  // the last 3 s: from (8.5 s, 0.85 s)
}

TEST(Progress, NoEstimateBeforeTheRunMovesAndNoneBelowZero) {
  run::ProgressEstimate est;
  est.add(0.0, 0.0);
  est.add(1.0, 0.0);  // a second of start-up without progress
  EXPECT_FALSE(est.seconds_left(1.0));
  est.add(2.0, 0.5);
  EXPECT_NEAR(*est.seconds_left(1.0), 0.5 * 2.0 / 0.5, 1e-12);
  EXPECT_EQ(*est.seconds_left(0.4), 0.0);  // past t_end (a rounding): nothing left
}

TEST(Progress, TheLineSaysAboutNotAtMost) {
  const std::string line = run::progress_text(1.102, 1.5, 102331, 2.0, 9.8);
  EXPECT_EQ(line, "t = 1.102 s of t_end 1.5 s (73.5 %), 102331 steps, 2.0 s elapsed, about 9.8 s left to t_end");
  EXPECT_EQ(line.find("at most"), std::string::npos);
  EXPECT_EQ(run::progress_text(0.5, 1.0, 10, 2.0, std::nullopt), "t = 0.5 s of t_end 1 s (50.0 %), 10 steps, 2.0 s elapsed");
}

}  // namespace
