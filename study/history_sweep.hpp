// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// e against St per history kernel over a sweep of one quantity: every point run with each kernel (× evaluator) and
// without the history force, the runs on an Executor.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/executor.hpp"
#include "study/sweep_points.hpp"
#include "study/table.hpp"

namespace imcol::study {

/// One series: a kernel and its evaluator, or "none" (without the history force).
struct HistorySeries {
  std::string kernel, evaluator;
  std::string name() const { return kernel == "none" ? kernel : kernel + " " + evaluator; }
};

/// none, then each kernel with each evaluator (repeats dropped); `evaluators` empty: the scene's own evaluator.
std::vector<HistorySeries> history_series(const std::vector<std::string>& kernels, const std::vector<std::string>& evaluators,
                                          const Scene& base);

/// One run: a sweep point with one series.
struct HistoryCell {
  int point = 0;
  double value = NAN;
  HistorySeries series;
  std::string status = "ok";  // ok | failed (the run threw: the message says why)
  std::string message;        // failed: the error; ok: why e is missing, if it is
  RunSummary summary;         // when ok
  bool ok() const { return status == "ok"; }
};

struct HistorySweepResult {
  std::string vary, column;
  std::vector<double> values;
  std::vector<HistorySeries> series;
  std::vector<HistoryCell> cells;  // point by point, series by series
  std::vector<bool> done;          // the cell ran (ok or failed)
  bool cancelled = false;
  std::size_t failed() const;
};

/// After each cell is taken in, on the deciding process, one call at a time.
using CellTaken = std::function<void(std::size_t i, const HistoryCell& cell)>;

/// Runs every point's scene (scenes[i] at values[i]) with every series on `ex` (kinematics only, as a sweep).
HistorySweepResult history_sweep(const std::vector<Scene>& scenes, const std::string& vary, const std::vector<double>& values,
                                 const std::vector<HistorySeries>& series, const Executor& ex, const Hooks& hooks = {},
                                 const CellTaken& taken = {});

/// history_sweep.csv's table: a row per point and series.
Table history_sweep_table(const HistorySweepResult& r);


}  // namespace imcol::study
