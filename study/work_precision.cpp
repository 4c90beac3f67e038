// SPDX-License-Identifier: BSD-3-Clause
#include "study/work_precision.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <map>

#include "core/errors.hpp"
#include "core/report.hpp"
#include "model/collision_model.hpp"
#include "run/simulate.hpp"
#include "run/summary_json.hpp"
#include "study/run_all.hpp"
#include "study/run_failure.hpp"
#include "study/work_precision_fit.hpp"

namespace imcol::study {

namespace work_precision_impl {  // this file's helpers: named, as study/ is built in unity batches

/// Output samples (events excluded) keyed by time: the gap (or z1) over D and the velocities.
using Samples = std::map<double, std::vector<double>>;  // time → (gap or z1)/D, u1[, u2]

Samples samples(const RunResult& r, double D) {
  auto col = [&](const std::string& name) {
    for (std::size_t i = 0; i < r.columns.size(); ++i)
      if (r.columns[i] == name) return static_cast<long>(i);
    return -1L;
  };
  const long ig = col("gap") >= 0 ? col("gap") : col("z1"), iu1 = col("u1"), iu2 = col("u2"), ie = col("event");
  Samples s;
  for (const auto& row : r.rows) {
    if (row[ie] != 0.0) continue;
    std::vector<double> v = {row[ig] / D, row[iu1]};
    if (iu2 >= 0) v.push_back(row[iu2]);
    s[row[0]] = v;
  }
  return s;
}

/// max over common output times of max(|Δgap|/D, |Δu|/u_scale); NaN if no common times.
double trajectory_error(const Samples& run, const Samples& ref, double u_scale) {
  double err = 0;
  std::size_t common = 0;
  for (const auto& [t, v] : run) {
    auto it = ref.lower_bound(t - 1e-12 * std::max(1.0, std::abs(t)));
    if (it == ref.end() || std::abs(it->first - t) > 1e-12 * std::max(1.0, std::abs(t))) continue;
    ++common;
    err = std::max(err, std::abs(v[0] - it->second[0]));
    for (std::size_t k = 1; k < v.size(); ++k) err = std::max(err, std::abs(v[k] - it->second[k]) / u_scale);
  }
  return common ? err : NAN;
}

double metric_of(const RunResult& r, bool collision) {
  return (collision ? r.summary.e : r.summary.u1_final_m_s).value_or(NAN);
}

/// The scene with one configuration's solver and history settings; atol = rtol.
Scene scene_for(const Scene& base, const LadderConfig& c, double rtol, double direct_step, double history_tol) {
  Scene sc = base;
  sc.solver.rtol = rtol;
  sc.solver.atol = rtol;
  sc.solver.integrator = c.integrator == LadderIntegrator::ida ? IntegratorMethod::ida : IntegratorMethod::cvode;
  sc.solver.linear_solver = c.integrator == LadderIntegrator::cvode_gmres ? LinearSolverChoice::gmres : LinearSolverChoice::dense;
  if (c.evaluator) {
    sc.history.evaluator = *c.evaluator;
    if (c.soe()) {
      sc.history.modes = 0;
      sc.history.tolerance = history_tol;
    } else {
      sc.history.direct_step = direct_step;
    }
  }
  return sc;
}

/// What one run tells: its wall time; for the reference and each rung's last run its metric, solver counts and
/// output samples; the rank that ran it. A run that threw says how (`failure`): a SolverError fails its rung (or,
/// the reference's, the study); anything else ends the study.
struct RunOutcome {
  RunFailure failure;
  double metric = NAN, wall_s = NAN;
  std::int64_t steps = 0, rhs = 0, lin_iters = 0;
  Samples samples;
  std::optional<SolverSummary> solver;  // the reference's
  std::vector<Effect> effects;          // the reference's
  int rank = 0;
};

void to_json(nlohmann::ordered_json& j, const RunOutcome& o) {
  j = {{"failure", o.failure}, {"metric", o.metric}, {"wall_s", o.wall_s}, {"steps", o.steps}, {"rhs", o.rhs},
       {"lin_iters", o.lin_iters}, {"samples", o.samples}, {"solver", o.solver ? nlohmann::ordered_json(*o.solver) : nlohmann::ordered_json(nullptr)}, {"effects", effects_to_json(o.effects)},
       {"rank", o.rank}};
}

void from_json(const nlohmann::ordered_json& j, RunOutcome& o) {
  j.at("failure").get_to(o.failure);
  j.at("metric").get_to(o.metric), j.at("wall_s").get_to(o.wall_s);
  j.at("steps").get_to(o.steps), j.at("rhs").get_to(o.rhs), j.at("lin_iters").get_to(o.lin_iters);
  j.at("samples").get_to(o.samples);
  o.solver = run::get_opt<SolverSummary>(j, "solver");
  o.effects = effects_of(j.at("effects"));
  j.at("rank").get_to(o.rank);
}

/// Runs run i of the plan (on whichever rank it was handed to).
RunOutcome run_one(const WorkPrecisionPlan& plan, std::size_t i, int rank) {
  RunOutcome o;
  o.rank = rank;
  try {
    const bool ref = i == 0;
    const auto& opt = plan.opt;
    const Scene sc = ref ? scene_for(plan.base, plan.ref_cfg, opt.ref_rtol, NAN, opt.ref_history_tol)
                         : scene_for(plan.base, plan.rung(i).cfg, plan.rung(i).rtol, plan.rung(i).direct_step, plan.rung(i).history_tol());
    const RunResult r = simulate(sc);
    o.wall_s = r.summary.wall_time_s;
    if (ref || plan.k(i) == opt.repeat - 1) {  // every run of a rung gives the same numbers: its last run's are kept
      const SolverStats& sol = r.summary.solver.stats;
      o.metric = metric_of(r, plan.collision);
      o.steps = sol.steps, o.rhs = sol.rhs_evals, o.lin_iters = sol.lin_iters;
      o.samples = samples(r, plan.base.spheres[0].diameter);
    }
    if (ref) {
      o.solver = r.summary.solver;
      o.effects = r.summary.effects;
    }
  } catch (const std::exception&) {
    o.failure = RunFailure::current();
  }
  return o;
}

/// The reference run's metric, its samples and the velocity scale of trajectory errors.
struct Reference {
  RunOutcome run;
  double value = NAN, u_scale = 0;
};

Reference reference_of(RunOutcome run, bool collision) {
  Reference ref;
  ref.run = std::move(run);
  ref.value = ref.run.metric;
  if (std::isnan(ref.value))
    throw SolverError("the reference run has no " + std::string(collision ? "e (no collision by t_end?)" : "final velocity"));
  for (const auto& [t, v] : ref.run.samples)
    for (std::size_t k = 1; k < v.size(); ++k) ref.u_scale = std::max(ref.u_scale, std::abs(v[k]));
  if (!(ref.u_scale > 0)) ref.u_scale = 1;
  return ref;
}

/// One rung from its runs: their median wall time and the errors against the reference. A run's solver failure
/// (the first in run order) fails the rung.
WorkPrecisionRow row_of(const WorkPrecisionPlan& plan, std::size_t r, const std::vector<RunOutcome>& outcomes, const Reference& ref) {
  const Rung& g = plan.rungs[r];
  const auto repeat = static_cast<std::size_t>(plan.opt.repeat);
  WorkPrecisionRow p;
  p.cfg = g.cfg;
  p.rtol = g.rtol;
  p.direct_step = g.direct_step;
  p.history_tol = g.history_tol();
  std::vector<double> times;
  for (std::size_t k = 0; k < repeat; ++k) {
    const RunOutcome& o = outcomes[1 + r * repeat + k];
    if (o.failure.kind == RunFailure::solver) {
      p.message = "solver failure: " + o.failure.what;
      return p;
    }
    times.push_back(o.wall_s);
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  const RunOutcome& last = outcomes[(r + 1) * repeat];
  p.ok = true;
  p.e = last.metric;
  p.err_e = std::abs(p.e - ref.value);
  p.err_traj = trajectory_error(last.samples, ref.run.samples, ref.u_scale);
  p.ms = 1e3 * times[times.size() / 2];
  p.steps = last.steps;
  p.rhs = last.rhs;
  p.lin_iters = last.lin_iters;
  if (std::isnan(p.e)) p.message = plan.collision ? "no e (no collision by t_end)" : "no final velocity";
  return p;
}

/// The outcomes of every run as they arrive on the deciding process, and the first run that ends the study.
struct Arrivals {
  std::vector<RunOutcome> outcomes;
  std::vector<std::exception_ptr> thrown;  // this process's runs: the exception itself, rethrown so
  std::vector<char> arrived;
  std::vector<int> per_rung, runs_by_rank;
  std::size_t stop;
  Arrivals(const WorkPrecisionPlan& plan, int ranks)
      : outcomes(plan.count()), thrown(plan.count()), arrived(plan.count(), 0), per_rung(plan.rungs.size(), 0),
        runs_by_rank(static_cast<std::size_t>(ranks), 0), stop(plan.count()) {}
};

/// Takes run i's outcome: counts it, tells of it (several ranks) and says whether to hand out more runs.
bool take_outcome(const WorkPrecisionPlan& plan, Arrivals& a, std::size_t i, RunOutcome&& o, int ranks, const RunNotice& notice) {
  a.outcomes[i] = std::move(o);
  a.arrived[i] = 1;
  const int rank = a.outcomes[i].rank;
  if (rank >= 0 && rank < ranks) ++a.runs_by_rank[static_cast<std::size_t>(rank)];
  if (ranks > 1 && notice) {
    if (i == 0 || ++a.per_rung[(i - 1) / static_cast<std::size_t>(plan.opt.repeat)] == plan.opt.repeat) notice(i, rank);
  }
  const int f = a.outcomes[i].failure.kind;
  if (f != RunFailure::none && (i == 0 || f != RunFailure::solver)) {
    a.stop = std::min(a.stop, i);
    return false;
  }
  return i > 0 || !std::isnan(a.outcomes[0].metric);  // a reference without its metric ends the study too
}

/// The reference and every rung's runs on the executor. A failed reference, or a run that threw anything but a
/// SolverError, is rethrown on the deciding process.
Arrivals run_outcomes(const WorkPrecisionPlan& plan, const Executor& ex, const Hooks& hooks, const RunNotice& notice) {
  Arrivals a(plan, ex.ranks);
  auto run = [&](std::size_t i) {
    if (ex.ranks == 1 && notice && (i == 0 || plan.k(i) == 0)) notice(i, -1);
    RunOutcome o = run_one(plan, i, ex.rank);
    a.thrown[i] = o.failure.thrown;
    return o;
  };
  auto take = [&](std::size_t i, RunOutcome&& o) { return take_outcome(plan, a, i, std::move(o), ex.ranks, notice); };
  run_all<RunOutcome>(ex, plan.count(), run, take, hooks);
  if (ex.deciding() && a.stop < plan.count()) {
    a.outcomes[a.stop].failure.thrown = a.thrown[a.stop];
    a.outcomes[a.stop].failure.rethrow();
  }
  return a;
}

/// The reference's own uncertainty, estimated as the error of the same settings one decade looser than the
/// reference (the tightest cvode-dense rung).
double reference_uncertainty(const std::vector<WorkPrecisionRow>& rows, const WorkPrecisionPlan& plan) {
  double ref_unc = 0;
  const double tightest = *std::min_element(plan.opt.rtols.begin(), plan.opt.rtols.end());
  for (const auto& p : rows)
    if (p.ok && p.cfg.integrator == LadderIntegrator::cvode_dense && p.cfg.evaluator == plan.ref_cfg.evaluator && p.rtol == tightest)
      ref_unc = p.err_e;
  return ref_unc;
}

/// Every run of rung r has arrived.
bool rung_complete(const WorkPrecisionPlan& plan, const Arrivals& a, std::size_t r) {
  const auto repeat = static_cast<std::size_t>(plan.opt.repeat);
  for (std::size_t k = 0; k < repeat; ++k)
    if (!a.arrived[1 + r * repeat + k]) return false;
  return true;
}

/// The result's heading: the scene, the reference and the settings it was run at.
WorkPrecisionResult result_heading(const WorkPrecisionPlan& plan, const Reference& ref) {
  WorkPrecisionResult res;
  res.scene = plan.base.name;
  res.metric = plan.metric();
  res.history = plan.history;
  res.reference = plan.ref_cfg;
  res.ref_rtol = plan.opt.ref_rtol;
  res.ref_history_tol = plan.opt.ref_history_tol;
  res.value = ref.value;
  res.wall_time_s = ref.run.wall_s;
  res.solver = ref.run.solver.value_or(SolverSummary{});
  res.effects = ref.run.effects;
  res.u_scale = ref.u_scale;
  res.repeat = plan.opt.repeat;
  res.skipped = plan.skipped;
  return res;
}

}  // namespace work_precision_impl

WorkPrecisionResult work_precision(const WorkPrecisionPlan& plan, const Executor& ex, const Hooks& hooks, const RunNotice& notice) {
  using namespace work_precision_impl;
  Arrivals a = run_outcomes(plan, ex, hooks, notice);
  if (!ex.deciding()) return {};
  if (!a.arrived[0]) {  // cancelled before the reference came
    WorkPrecisionResult none;
    none.cancelled = true;
    return none;
  }
  const Reference ref = reference_of(std::move(a.outcomes[0]), plan.collision);
  WorkPrecisionResult res = result_heading(plan, ref);
  for (std::size_t r = 0; r < plan.rungs.size(); ++r) {
    if (rung_complete(plan, a, r)) res.rows.push_back(row_of(plan, r, a.outcomes, ref));
    else res.cancelled = true;
  }
  res.uncertainty = reference_uncertainty(res.rows, plan);
  res.order_floor = std::max(10 * res.uncertainty, 1e-15);  // fits exclude errors within 10x of it
  res.orders = observed_orders(plan.configs, res.rows, res.order_floor);
  res.cheapest = cheapest_settings(res.rows);
  res.runs_by_rank = std::move(a.runs_by_rank);
  return res;
}

}  // namespace imcol::study
