// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// imcol calibrate's progress line on a terminal (stderr): the stage, its work items done, the evaluations, the best
// rms so far, the time taken and an estimate of the time left; and when each stage ended, for the closing table.
#include <array>
#include <cstddef>
#include <mutex>
#include <string>

#include "calibrate/search.hpp"
#include "core/timing.hpp"

namespace imcol {

/// When each stage ended (s after the search began; NaN: the stage did not run).
struct StageTimes {
  std::array<double, 5> end;  // by calib::Stage
  /// The stage's wall time: from the end of the stage before it (or the start) to its own end; NaN if it did not run.
  double wall(calib::Stage s) const;
};

class ProgressLine {
 public:
  /// `show`: draw the line (rank 0 on a terminal); `d` parameters; `workers`: threads on all ranks; `unit` of the rms.
  ProgressLine(bool show, std::size_t d, const calib::SearchOptions& opt, int workers, std::string unit);

  /// An evaluation finished (any thread of this process) and took `wall_s`.
  void add_evaluation(double wall_s);
  /// The callback search calls after each finished work item.
  calib::Progress callback();
  /// Ends the line.
  void finish();
  StageTimes stage_times() const;

 private:
  void update(calib::Stage s, std::size_t done, std::size_t items, std::size_t evaluations, double best);
  double time_left(calib::Stage s, std::size_t done, std::size_t items, double t) const;

  bool show_;
  std::size_t d_;
  calib::SearchOptions opt_;
  int workers_;
  std::string unit_;
  WallClock::time_point start_;
  mutable std::mutex mu_;
  double eval_wall_ = 0;  // sum of this process's evaluation times
  long eval_count_ = 0;
  StageTimes times_;
  bool drawn_ = false;
};

}  // namespace imcol
