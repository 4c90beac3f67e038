// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// imcol calibrate's progress line on a terminal (stderr): the stage, its work items done, the evaluations, the best
// rms so far, the time taken and an estimate of the time left.
#include <cstddef>
#include <mutex>
#include <string>

#include "calibrate/search.hpp"
#include "core/timing.hpp"
#include "study/calibrate.hpp"

namespace imcol {

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
  study::StageTimes times_;  // when each stage's last item ended, for the estimate
  bool drawn_ = false;
};

}  // namespace imcol
