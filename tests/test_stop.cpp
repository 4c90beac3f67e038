// SPDX-License-Identifier: BSD-3-Clause
// core/stop.hpp through the layers: a stop requested from another thread ends simulate() with Interrupted within a
// bounded time, a sweep stopped mid-run returns cancelled with its finished points only, `imcol sweep` stopped by
// SIGINT leaves no output folder and exits 130, and a stop never requested leaves a run's results bit-identical;
// run/progress_estimate.hpp's readings of a progress meter.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <thread>

#include "core/scene_files.hpp"
#include "core/timing.hpp"
#include "core/work_scope.hpp"
#include "imcol_process.hpp"
#include "run/progress_estimate.hpp"
#include "run/simulate.hpp"
#include "study/sweep.hpp"

namespace imcol {
namespace {

namespace fs = std::filesystem;

/// The shipped scene `default` with a step cap that makes its run take many seconds (reduced-order, 6.5 million steps;
/// at 5e-8, 650 000 steps, an idle machine finished it in 0.5–0.6 s, before the sweep's stop at 0.6 s). Every run of
/// it here is stopped within its first second.
Scene slow_default_scene() { return load_scene(find_scene("default"), {{"solver.max_step", "5e-9"}, {"solver.step_budget", "1e9"}}); }

/// Requests `source`'s stop after `delay` on a thread of its own; when() is the time it did.
struct DelayedStop {
  DelayedStop(const StopSource& source, std::chrono::milliseconds delay)
      : thread([this, source, delay] {
          std::this_thread::sleep_for(delay);
          at = WallClock::now();
          source.request_stop();
        }) {}
  ~DelayedStop() { thread.join(); }
  WallClock::time_point at{};
  std::thread thread;
};

TEST(StopRequest, SimulateEndsWithInterruptedSoonAfterTheRequest) {
  const Scene sc = slow_default_scene();
  StopSource source;
  std::optional<WallClock::time_point> thrown;
  {
    WorkScope scope({source.token(), nullptr});
    DelayedStop stop(source, std::chrono::milliseconds(300));
    try {
      simulate(sc, false, Recording::kinematics);
    } catch (const Interrupted&) {
      thrown = WallClock::now();
    }
  }
  ASSERT_TRUE(thrown.has_value()) << "the run ended before the stop (make its scene slower)";
  EXPECT_TRUE(source.stop_requested());
}

TEST(StopRequest, TheRequestReachesTheRunWithinHalfASecond) {
  const Scene sc = slow_default_scene();
  StopSource source;
  double latency = -1;
  {
    WorkScope scope({source.token(), nullptr});
    DelayedStop stop(source, std::chrono::milliseconds(300));
    try {
      simulate(sc, false, Recording::full);
    } catch (const Interrupted&) {
      latency = std::chrono::duration<double>(WallClock::now() - stop.at).count();
    }
  }
  ASSERT_GE(latency, 0.0);
  EXPECT_LT(latency, 0.5);
}

TEST(StopRequest, ASweepStoppedMidRunReturnsItsFinishedPointsOnly) {
  const std::string path = find_scene("default");
  const Scene fast = load_scene(path), slow = slow_default_scene();
  study::Hooks hooks;
  StopSource source;
  hooks.stop = source.token();
  const auto t0 = WallClock::now();
  study::SweepResult r;
  {
    DelayedStop stop(source, std::chrono::milliseconds(600));
    r = study::run_sweep({fast, slow, slow}, "velocity", {0.3, 0.3, 0.3}, study::threads(2), hooks);
  }
  EXPECT_LT(seconds_since(t0), 2.0);  // the slow points in flight ended within a step of the request
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.done[0] && r.points[0].ok);
  EXPECT_FALSE(r.done[1]);
  EXPECT_FALSE(r.done[2]);
  EXPECT_EQ(r.failed(), 0u);  // an interrupted point is no failed point
}

TEST(StopRequest, AStopNeverRequestedLeavesTheRunBitIdentical) {
  const Scene sc = load_scene(find_scene("default"));
  const RunResult plain = simulate(sc);
  StopSource source;
  ProgressMeter meter;
  RunResult watched;
  {
    WorkScope scope({source.token(), &meter});
    watched = simulate(sc);
  }
  EXPECT_EQ(watched.rows, plain.rows);
  EXPECT_EQ(watched.summary.e, plain.summary.e);
  EXPECT_EQ(watched.summary.solver.stats.steps, plain.summary.solver.stats.steps);
  const auto [done, total] = meter.read();
  EXPECT_EQ(total, sc.solver.t_end);
  EXPECT_EQ(done, watched.rows.back()[0]);  // the last sample's time
}

TEST(StopRequest, SigintToASweepLeavesNoFolderAndExits130) {
  const fs::path dir = fs::temp_directory_path() / ("imcol_sigint_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const pid_t pid = test::start_imcol("sweep " + find_scene("default") + " --set solver.max_step=5e-8 --set solver.step_budget=1e8"
                                      " --vary velocity --from 0.2 --to 0.4 --points 4 --jobs 2 --no-plot --out swept",
                                      dir.string());
  ASSERT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_TRUE(fs::is_empty(dir)) << "a folder or a staging folder was left";
  fs::remove_all(dir);
}

TEST(ProgressReading, TheSecondsLeftFallBackOnTheMeanRateAndAreZeroAtTheEnd) {
  const run::ProgressEstimate none;
  EXPECT_EQ(run::eta_seconds(none, 2.0, 1.0, 4.0), 6.0);  // 2 s for 1 of 4: 6 s for the other 3
  EXPECT_EQ(run::eta_seconds(none, 2.0, 4.0, 4.0), 0.0);
  EXPECT_FALSE(run::eta_seconds(none, 2.0, 0.0, 4.0).has_value());
}

TEST(ProgressReading, TheFollowerReportsOnlyWhenTheWorkAdvanced) {
  ProgressMeter meter;
  run::ProgressFollower follower(meter);
  EXPECT_FALSE(follower.poll().has_value());  // nothing reported yet
  meter.set(1, 4);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const auto p = follower.poll();
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->done, 1.0);
  EXPECT_EQ(p->total, 4.0);
  EXPECT_TRUE(std::isfinite(p->eta_s) && p->eta_s > 0);
  EXPECT_FALSE(follower.poll().has_value());  // no advance since
  meter.set(4, 4);
  const auto last = follower.poll();
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ(last->eta_s, 0.0);
}

}  // namespace
}  // namespace imcol
