// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The progress of long work as (done, total, seconds left): done and total in the work's own measure (a run: simulated
// s of t_end; a study: finished runs of all). The seconds left are projected from the rate over the last kWindow s of
// wall time. The command line's progress lines and the Python module's progress callbacks read it.
#include <deque>
#include <optional>
#include <utility>

#include "core/progress_meter.hpp"
#include "core/timing.hpp"

namespace imcol::run {

/// The wall time left to `total`, projected from the rate (done per wall s) over the last kWindow s of wall time:
/// remaining = (total − done) · Δwall / Δdone over that window. An estimate, not a bound: a run's step size can shrink
/// later (a contact, a stiff resting contact, the direct history evaluator's cost growing with the run), and a run can
/// stop before t_end (e measured, at rest).
class ProgressEstimate {
 public:
  static constexpr double kWindow = 3.0;  // s of wall time
  /// `done` reached `wall` s after the start (both non-decreasing).
  void add(double wall, double done);
  /// Wall seconds to `total` at the recent rate; none before `done` has advanced.
  std::optional<double> seconds_left(double total) const;

 private:
  std::deque<std::pair<double, double>> points_;  // (wall s, done): the newest, and the last one at least kWindow older
};

/// One reading: done of total, and the seconds left (finite, >= 0).
struct Progress {
  double done = 0, total = 0, eta_s = 0;
};

/// The seconds left: the recent rate's projection, else the mean rate since the start (`elapsed` s for `done`); 0 once
/// done >= total; none while nothing is done.
std::optional<double> eta_seconds(const ProgressEstimate& estimate, double elapsed, double done, double total);

/// Readings of work its caller counts (a command line's progress line): the seconds left from the start of the timer.
class ProgressTimer {
 public:
  /// `done` of `total` now; none while nothing is done (or total <= 0).
  std::optional<Progress> at(double done, double total);

 private:
  WallClock::time_point start_ = WallClock::now();
  ProgressEstimate estimate_;
};

/// Follows a ProgressMeter set by another thread (the work), from the thread that reports it.
class ProgressFollower {
 public:
  explicit ProgressFollower(const ProgressMeter& meter) : meter_(meter) {}
  /// The meter now, when its `done` advanced since the last reading given (and is > 0); none otherwise.
  std::optional<Progress> poll();

 private:
  const ProgressMeter& meter_;
  ProgressTimer timer_;
  double last_done_ = 0;
};

}  // namespace imcol::run
