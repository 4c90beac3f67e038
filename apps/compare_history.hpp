// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol history`: one scene with every history kernel × evaluator (and none), side by side (the engine:
// study/history.hpp).
#include <string>
#include <vector>

#include "apps/sweep.hpp"
#include "core/scene.hpp"
#include "study/history.hpp"

namespace imcol {

struct HistoryCompareOptions {
  std::vector<std::string> kernels = choice_names<KernelKind>();  // every shipped kernel
  std::vector<std::string> evaluators = {"soe-step", "soe", "direct"};
  bool evaluators_given = false;  // --evaluators: a sweep otherwise runs the scene's own evaluator only
  std::string out;   // default out/<scene>-history (a sweep: out/<scene>-history_<quantity>)
  bool plot = true;
  SweepOptions sweep;  // sweep.vary empty: the scene alone; else vary, from, to, points, spacing, jobs
};

using study::with_history_kernel;

/// --kernels and --evaluators: unknown names refused (InputError).
void check_history_choices(const HistoryCompareOptions& opt);

/// Prints the table, writes DIR/history.csv, DIR/history_forces.csv (f_H of sphere 1 at the output samples, the
/// events and every solver step near contact; the table's peak is taken over the same samples) and DIR/history.png.
int compare_history(const std::string& scene_path, const std::vector<Override>& overrides, const HistoryCompareOptions& opt);

}  // namespace imcol
