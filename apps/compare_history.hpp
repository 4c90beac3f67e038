// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol history`: one scene with every history kernel × evaluator (and none), side by side.
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace imcol {

struct HistoryCompareOptions {
  std::vector<std::string> kernels = choice_names<KernelKind>();  // every shipped kernel
  std::vector<std::string> evaluators = {"soe-step", "soe", "direct"};
  std::string out;   // default out/<scene>-history
  bool plot = true;
};

/// Prints the table, writes DIR/history.csv, DIR/history_forces.csv and DIR/history.png (matplotlib).
int compare_history(const std::string& scene_path, const std::vector<Override>& overrides, const HistoryCompareOptions& opt);

}  // namespace imcol
