// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Work-precision ladders of a collision scene: what accuracy costs. A ladder of tolerances for each integrator and
// history evaluator (for the direct evaluator, of its step), each run compared with one reference run at the
// tightest settings: e (or the final velocity) and the trajectory against the reference's, the median wall time, the
// observed orders (err ~ rtol^a, err ~ steps^-p) and the cheapest setting per target error.
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/choices.hpp"
#include "core/scene.hpp"
#include "run/run_summary.hpp"
#include "study/executor.hpp"
#include "study/table_column.hpp"

namespace imcol::study {

/// The direct evaluator's step multiples: below 0.1 its cost, quadratic in the number of steps, exceeds a hundred
/// times the default's; above 100 the step is longer than any contact.
inline constexpr double kDirectStepMin = 0.1, kDirectStepMax = 100;

struct WorkPrecisionOptions {
  std::vector<double> rtols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  std::vector<std::string> integrators = {"cvode-dense", "cvode-gmres", "ida"};
  std::vector<std::string> evaluators;  // soe-step, soe, direct; default all three if the scene has history, else none
  std::vector<double> direct_steps = {4, 2, 1, 0.5, 0.25};  // direct: multiples of its default step
  double direct_rtol = 1e-10;           // direct: the integrator tolerance while its step is varied
  double ref_rtol = 1e-13;              // reference: cvode dense, atol = rtol, soe fit tolerance ref_history_tol
  double ref_history_tol = 1e-11;
  int repeat = 3;                       // runs per setting; the median wall time is reported
  bool add_history = false;             // add the history effect (Basset) to a scene without it
};

/// The integrator of a ladder with its linear solver: CVODE dense, CVODE GMRES, IDA (dense).
enum class LadderIntegrator { cvode_dense, cvode_gmres, ida };
std::string to_string(LadderIntegrator i);  // cvode-dense | cvode-gmres | ida

/// One integrator with one history evaluator (none: the scene has no history).
struct LadderConfig {
  LadderIntegrator integrator = LadderIntegrator::cvode_dense;
  std::optional<HistoryEvaluator> evaluator;
  std::string integrator_name() const { return to_string(integrator); }
  std::string evaluator_name() const { return evaluator ? std::string(imcol::to_string(*evaluator)) : "none"; }  // none | soe-step | soe | direct
  std::string label() const { return evaluator ? integrator_name() + " / " + evaluator_name() : integrator_name(); }
  bool soe() const { return evaluator == HistoryEvaluator::soe || evaluator == HistoryEvaluator::soe_step; }
  bool direct() const { return evaluator == HistoryEvaluator::direct; }
};

/// One setting of a ladder: rtol along the rtols, or for the direct evaluator its step (s) at direct_rtol.
struct Rung {
  LadderConfig cfg;
  double rtol = NAN, direct_step = NAN;
  double history_tol() const;  // the soe fit tolerance (soe evaluators), else NaN
};

/// The runs of a ladder, numbered: 0 is the reference, then each rung's `repeat` runs (1 + rung * repeat + k).
struct WorkPrecisionPlan {
  Scene base;  // with history added by add_history
  WorkPrecisionOptions opt;
  bool history = false, collision = false;  // collision: the metric is e, else the final velocity
  LadderConfig ref_cfg;
  std::vector<LadderConfig> configs;
  std::vector<std::string> skipped;  // combinations the solvers cannot do, with the reason
  std::vector<Rung> rungs;
  std::size_t count() const { return 1 + rungs.size() * static_cast<std::size_t>(opt.repeat); }
  const Rung& rung(std::size_t i) const { return rungs[(i - 1) / static_cast<std::size_t>(opt.repeat)]; }
  int k(std::size_t i) const { return static_cast<int>((i - 1) % static_cast<std::size_t>(opt.repeat)); }
  std::string metric() const { return collision ? "e" : "u_end"; }
};

/// An InputError naming the first option out of its range.
void check_work_precision_options(const WorkPrecisionOptions& opt);

/// Checks the options and lays out the runs of `base` (not a coupled scene).
WorkPrecisionPlan plan_work_precision(Scene base, const WorkPrecisionOptions& opt);

/// One rung against the reference: the metric, its error, the trajectory error, the median wall time (ms) and the
/// solver's counts of the rung's last run; or why it failed (a solver failure).
struct WorkPrecisionRow {
  LadderConfig cfg;
  double rtol = NAN, direct_step = NAN, history_tol = NAN;
  bool ok = false;
  std::string message;
  double e = NAN, err_e = NAN, err_traj = NAN, ms = NAN;
  long steps = 0, rhs = 0, lin_iters = 0;
};

/// Per configuration: err ~ x^exponent (x = rtol, or direct_step) and err ~ steps^-order_in_steps, fitted over the
/// errors above the result's order_floor.
struct ObservedOrder {
  std::string config, vs;
  std::optional<double> exponent, order_in_steps;
  std::size_t points = 0;
};

/// For a target error: the fastest row that reaches it and keeps it at every tighter rung of its ladder.
struct CheapestSetting {
  double target = NAN;
  std::optional<std::size_t> row;
};

struct WorkPrecisionResult {
  std::string scene, metric;  // metric: e | u_end
  bool history = false;
  LadderConfig reference;
  double ref_rtol = NAN, ref_history_tol = NAN;
  double value = NAN, uncertainty = NAN, wall_time_s = NAN;  // the reference's metric, its uncertainty, its wall time
  SolverSummary solver;                                      // the reference's solver settings and statistics
  std::vector<Effect> effects;                               // the reference's effects
  double u_scale = NAN;                                      // velocity scale of trajectory errors, m/s
  int repeat = 1;
  std::vector<std::string> skipped;
  std::vector<WorkPrecisionRow> rows;
  double order_floor = NAN;
  std::vector<ObservedOrder> orders;
  std::vector<CheapestSetting> cheapest;  // targets 1e-3, 1e-6, 1e-9
  std::vector<int> runs_by_rank;          // runs each rank ran
  bool cancelled = false;                 // the hooks stopped it: rows hold the rungs that finished
};

/// Told of a run: starting on this process (rank -1; one rank alone: the reference and each rung's first run), or
/// arrived from `rank` (several ranks: the reference and each rung's last run to arrive).
using RunNotice = std::function<void(std::size_t run, int rank)>;

/// Runs the plan on `ex`. The deciding process returns the result; other ranks an empty one. A failed reference, or
/// a run that threw anything but a SolverError, is rethrown on the deciding process.
WorkPrecisionResult work_precision(const WorkPrecisionPlan& plan, const Executor& ex, const Hooks& hooks = {},
                                   const RunNotice& notice = {});

/// A column of the rows' table (work_precision.csv).
using WorkPrecisionColumn = RowColumn<WorkPrecisionRow>;

/// The table's columns, in order; `metric` names the metric's columns.
std::vector<WorkPrecisionColumn> work_precision_columns(const std::string& metric);

}  // namespace imcol::study
