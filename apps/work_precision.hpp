// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol work-precision`: what accuracy costs. The ladders of study/work_precision.hpp (a coupled scene: those of
// study/work_precision_flow.hpp), printed and written.
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "study/work_precision.hpp"

namespace imcol {

struct WorkPrecisionOptions : study::WorkPrecisionOptions {
  std::string out;                          // default out/<scene>-work_precision
  bool plot = true;
  std::vector<std::string> ladder_options;  // --rtol, --atol, --integrator as given: the ladder sets them (refused but for a coupled scene)
};

/// Prints the table, the observed orders and the cheapest settings; writes DIR/work_precision.csv,
/// DIR/work_precision.json and DIR/work_precision.png.
int work_precision(const std::string& scene_path, const std::vector<Override>& overrides, const WorkPrecisionOptions& opt);

}  // namespace imcol
