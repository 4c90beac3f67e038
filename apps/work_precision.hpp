// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol work-precision`: what accuracy costs. A ladder of tolerances for each integrator and history
// evaluator, each run compared with one reference run at the tightest settings.
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace imcol {

/// The direct evaluator's step multiples (--direct-steps): below 0.1 its cost, quadratic in the number of steps, exceeds
/// a hundred times the default's; above 100 the step is longer than any contact.
inline constexpr double kDirectStepMin = 0.1, kDirectStepMax = 100;

struct WorkPrecisionOptions {
  std::string out;                                                  // default out/<scene>-work_precision
  std::vector<double> rtols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  std::vector<std::string> integrators = {"cvode-dense", "cvode-gmres", "ida"};
  std::vector<std::string> evaluators;  // soe-step, soe, direct; default all three if the scene has history, else none
  std::vector<double> direct_steps = {4, 2, 1, 0.5, 0.25};  // direct: multiples of its default step
  double direct_rtol = 1e-10;           // direct: the integrator tolerance while its step is varied
  double ref_rtol = 1e-13;              // reference: cvode dense, atol = rtol, soe fit tolerance ref_history_tol
  double ref_history_tol = 1e-11;
  int repeat = 3;                       // runs per setting; the median wall time is reported
  bool add_history = false;             // add the history effect (Basset) to a scene without it
  bool plot = true;
  std::vector<std::string> ladder_options;  // --rtol, --atol, --integrator as given: the ladder sets them (refused but for a coupled scene)
};

/// Prints the table, the observed orders and the cheapest settings; writes DIR/work_precision.csv,
/// DIR/work_precision.json and DIR/work_precision.png.
int work_precision(const std::string& scene_path, const std::vector<Override>& overrides, const WorkPrecisionOptions& opt);

}  // namespace imcol
