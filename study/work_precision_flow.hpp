// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Work-precision of a coupled scene (the `flow` effect): what the flow kernel's accuracy costs. The ladder is the grid
// (cells per diameter) at the scene's flow step rule, then the flow step (cfl) at the scene's grid, each run compared
// with the finest run of its ladder (MODEL.md §5: convergence is in cells per diameter and in Δt).
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.hpp"
#include "study/executor.hpp"
#include "study/work_precision.hpp"

namespace imcol::study {

struct FlowLadderOptions {
  std::vector<int> cells = {16, 24, 32, 48};    // cells per diameter; the last is the grid ladder's reference
  std::vector<double> cfls = {1.0, 0.5, 0.25};  // flow step dt = cfl h / U; the last is the step ladder's reference
};

/// One rung: its ladder (grid | step), grid and cfl; e, |e − e_finest| (0 for the finest), e_instant, the wall time
/// (s), the flow steps, ms per flow step, Krylov iterations per step and the run's flow block (summary.json).
struct FlowLadderRow {
  std::string ladder;
  int cells = 0;
  double cfl = 0;
  bool reference = false;  // the finest rung of its ladder
  double dt = NAN, e = NAN, err = NAN, e_instant = NAN, wall_time_s = NAN, ms_per_step = NAN, krylov = NAN;
  long steps = 0;
  std::optional<FlowSummary> flow;  // the run's flow statistics
};

struct FlowLadderResult {
  std::string scene;
  std::vector<FlowLadderRow> rows;  // the grid ladder, then the step ladder
  int ranks = 1;
  bool cancelled = false;  // the hooks stopped it: no rows (each needs its ladder's finest rung)
};

/// The scene with the given keys set over the caller's own (a rung: flow.cells_per_diameter, flow.cfl).
using SceneLoader = std::function<Scene(const std::vector<Override>& keys)>;

/// An InputError for ladders of fewer than two rungs, a grid or cfl out of range, or a scene with flow.dt.
void check_flow_ladder(const Scene& base, const FlowLadderOptions& opt);

/// Runs both ladders of `base` (checked first) on `ex`; a failed rung is rethrown on the deciding process. The
/// deciding process returns the result, other ranks an empty one. `notice(rung, rank)`: as in work_precision.
FlowLadderResult flow_ladder(const Scene& base, const SceneLoader& load, const FlowLadderOptions& opt, const Executor& ex,
                             const Hooks& hooks = {}, const RunNotice& notice = {});

/// The rungs' ladder, cells and cfl, in run order (for a notice).
struct FlowRung {
  std::string ladder;
  int cells;
  double cfl;
};
std::vector<FlowRung> flow_rungs(const Scene& base, const FlowLadderOptions& opt);

}  // namespace imcol::study
