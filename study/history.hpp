// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The history-force kernels and evaluators compared on one scene: a run with each kernel × evaluator and one without
// the history force, each against its kernel's direct evaluation.
#include <map>
#include <string>
#include <vector>

#include "run/simulate.hpp"
#include "study/executor.hpp"
#include "study/table.hpp"

namespace imcol::study {

/// The scene with the history force of `kernel` evaluated by `evaluator`, or without it ("none").
Scene with_history_kernel(const Scene& base, const std::string& kernel, const std::string& evaluator);

/// Unknown kernel or evaluator names refused: InputError("--kernels" or "--evaluators", the name).
void check_history_choices(const std::vector<std::string>& kernels, const std::vector<std::string>& evaluators);

/// One kernel × evaluator's run ("none", "-": without the history force).
struct HistoryRun {
  std::string kernel, evaluator;
  RunResult run;
  double metric = NAN;    // e (collision) or final velocity (free sphere)
  double peak = 0;        // max |f_H| at the samples force_trace keeps, N
  double d_metric = NAN;  // |metric − reference| (the reference: the kernel's direct evaluation)
  double d_force = NAN;   // max |f_H − f_H,ref| / peak_ref over the output samples both have
};

struct HistoryResult {
  bool collision = false;        // e is the metric (else the final velocity of a free sphere)
  std::vector<HistoryRun> rows;  // none first, then kernel by kernel, evaluator by evaluator
  bool cancelled = false;
};

/// Runs `base` without the history force, then with each kernel and evaluator, one after the other. Throws
/// InputError for a scene without a liquid or an unknown name.
HistoryResult compare_history(const Scene& base, const std::vector<std::string>& kernels, const std::vector<std::string>& evaluators,
                              const Hooks& hooks = {});

/// f_hist1 at every sample the run kept (output samples, events, solver steps near contact), by time.
std::map<double, double> force_trace(const RunResult& r);

/// history.csv's table: a row per run.
Table history_table(const HistoryResult& r);

}  // namespace imcol::study
