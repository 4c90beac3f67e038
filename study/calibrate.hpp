// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A calibration (docs/calibration.md): the staged search of calibrate/search.hpp from the inputs' start values, its
// work items on an Executor; then, on the deciding process, the fitted run (a trajectory's) and the held-out
// measurement scored under the fitted values.
#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/search.hpp"
#include "run/simulate.hpp"
#include "study/calibrate_inputs.hpp"
#include "study/executor.hpp"

namespace imcol::study {

/// When each stage ended (s after the search began; NaN: the stage did not run).
struct StageTimes {
  std::array<double, 5> end;  // by calib::Stage
  StageTimes();
  /// The stage's wall time: from the end of the stage before it (or the start) to its own end; NaN if it did not run.
  double wall(calib::Stage s) const;
};

struct CalibrationResult {
  calib::SearchResult search;                 // its evaluations by stage, then work item (sort_evaluations)
  StageTimes stage_times;
  double wall_s = 0;                          // the search's wall time
  int jobs = 1, ranks = 1;                    // threads a process, processes
  std::optional<calib::Evaluation> validation;  // the held-out measurement under the fitted values
  std::optional<RunResult> best_run;          // a trajectory's fitted run
  std::string best_run_error;                 // why it is missing
  std::string best_run_warning;               // the fitted run scored otherwise than the search did
  bool cancelled = false;                     // stopped before the search's end: the result holds what finished
};

/// Evaluations kept from an earlier search (the command's --cache): find(values) from any thread; keep(bytes) on the
/// deciding process with each finished work item's evaluations (calibrate/evaluation_bytes.hpp) before the search
/// uses them.
struct EvaluationStore {
  std::function<std::optional<calib::Evaluation>(const std::vector<double>&)> find;
  std::function<void(const std::string&)> keep;
};

/// Finer reports than Hooks, for a terminal's progress line: `items` after each work item (the deciding process),
/// `evaluated(wall_s)` after each evaluation run on this process (any thread; not those found in the store).
struct CalibrationWatch {
  calib::Progress items;
  std::function<void(double wall_s)> evaluated;
};

/// The most evaluations the search makes for d parameters under `opt` (Hooks.progress's total).
std::size_t evaluation_budget(std::size_t d, const calib::SearchOptions& opt);

/// The evaluations in an order that does not depend on where or when they ran: by stage, then work item, each item's
/// own in the order it made them.
void sort_evaluations(calib::SearchResult& r);

/// Scores one set of values on a measurement; never throws (a failure is an evaluation that is not ok).
calib::Evaluation score(const CalibrationInputs& in, const calib::Measurement& m, const std::optional<calib::TrajectoryWindow>& w,
                        const std::vector<double>& values);

/// Runs the calibration on `ex`. hooks.progress(done, total) after each evaluation on this process (all of them
/// without MPI; total: evaluation_budget, and a last call with done == total at the end); hooks.cancelled() before each
/// evaluation and work item: once true, none further starts and the result holds what finished, `cancelled` set.
/// Every process calls it alike; the result is complete on the deciding one.
CalibrationResult run_calibration(const CalibrationInputs& in, const Executor& ex, const Hooks& hooks = {},
                                  const CalibrationWatch& watch = {}, const EvaluationStore& store = {});

}  // namespace imcol::study
