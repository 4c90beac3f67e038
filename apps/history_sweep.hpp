// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol history SCENE --vary Q --from A --to B --points N`: e against St per history kernel over a sweep of one
// quantity (imcol sweep's quantities and spacing), the runs in parallel.
#include <string>
#include <vector>

#include "apps/compare_history.hpp"
#include "core/scene.hpp"

namespace imcol {

/// Runs every point with each kernel (× evaluator) and without the history force; prints the table and writes
/// DIR/history_sweep.csv (a row per point and kernel: St, e, status), DIR/history_sweep.json and
/// DIR/history_sweep.png. Returns 0, or 3 if any run failed (its row says why).
int history_sweep(const std::string& scene_path, const std::vector<Override>& overrides, const HistoryCompareOptions& opt);

}  // namespace imcol
