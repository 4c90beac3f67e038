// SPDX-License-Identifier: BSD-3-Clause
// The runs of a work-precision ladder (study/work_precision.hpp): the options checked, the integrator × evaluator
// combinations the solvers can do, and their rungs.
#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "model/collision_model.hpp"
#include "study/work_precision.hpp"

namespace imcol::study {

void check_work_precision_options(const WorkPrecisionOptions& opt) {
  if (opt.repeat < 1) throw InputError("--repeat", "repeat", "must be >= 1");
  if (opt.rtols.empty()) throw InputError("--rtols", "rtols", "give at least one tolerance");
  for (double r : opt.rtols)
    if (!(r >= 1e-14 && r < 1)) throw InputError("--rtols", "rtols", "each tolerance must lie in [1e-14, 1)");
  if (!(opt.ref_rtol >= 1e-14 && opt.ref_rtol < 1)) throw InputError("--ref-rtol", "ref_rtol", "must lie in [1e-14, 1)");
  if (!(opt.direct_rtol >= 1e-14 && opt.direct_rtol < 1)) throw InputError("--direct-rtol", "direct_rtol", "must lie in [1e-14, 1)");
  if (!(opt.ref_history_tol >= 1e-13 && opt.ref_history_tol < 0.1))
    throw InputError("--ref-history-tolerance", "ref_history_tolerance", "must lie in [1e-13, 0.1)");
  for (double h : opt.direct_steps)
    if (!(h >= kDirectStepMin && h <= kDirectStepMax))
      throw InputError("command line", "--direct-steps", "each multiple must lie in [" + fmt_number(kDirectStepMin) + ", " +
                                                            fmt_number(kDirectStepMax) + "] (got " + fmt_number(h) + ")");
}

namespace work_precision_plan_impl {  // this file's helpers: named, as study/ is built in unity batches

/// The history evaluators to compare (all three by default where the scene has history; "none" without it); checks
/// the integrators too.
std::vector<std::string> evaluators_for(const WorkPrecisionOptions& opt, bool history) {
  std::vector<std::string> evaluators = opt.evaluators;
  if (evaluators.empty()) evaluators = history ? std::vector<std::string>{"soe-step", "soe", "direct"} : std::vector<std::string>{"none"};
  for (const auto& e : evaluators) {
    if (e != "soe" && e != "soe-step" && e != "direct" && e != "none")
      throw InputError("--evaluators", e, "unknown evaluator (expected soe, soe-step, direct)");
    if (e != "none" && !history)
      throw InputError("--evaluators", e, "the scene has no history effect (list it in `effects`, or pass --add-history)");
  }
  for (const auto& i : opt.integrators)
    if (i != "cvode-dense" && i != "cvode-gmres" && i != "ida")
      throw InputError("--integrators", i, "unknown integrator (expected cvode-dense, cvode-gmres, ida)");
  return evaluators;
}

/// Every evaluator with every integrator; a combination the solvers cannot do goes to `skipped` with its reason.
std::vector<LadderConfig> configs_for(const std::vector<std::string>& evaluators, const WorkPrecisionOptions& opt,
                                      std::vector<std::string>& skipped) {
  std::vector<LadderConfig> configs;
  for (const auto& ev : evaluators)
    for (const auto& in : opt.integrators) {
      if (in == "cvode-gmres" && ev != "soe") {
        skipped.push_back(in + (ev == "none" ? "" : " / " + ev) +
                          ": gmres needs the memory modes of the soe history evaluator (its preconditioner)");
        continue;
      }
      configs.push_back({in, ev});
    }
  return configs;
}

/// The direct evaluator's base step: the scene's, or the model's automatic step (read off a model built, not run).
double direct_base_step(const Scene& base, const std::vector<std::string>& evaluators) {
  double h_direct = base.history.direct_step;
  if (std::count(evaluators.begin(), evaluators.end(), "direct") && !(h_direct > 0)) {
    Scene probe = base;
    probe.history.evaluator = HistoryEvaluator::direct;
    h_direct = model::CollisionModel(probe).history_options().direct_step;
  }
  return h_direct;
}

/// The direct evaluator's accuracy is set by its step: its ladder varies the step at a tight rtol.
std::vector<Rung> ladder_rungs(const std::vector<LadderConfig>& configs, const WorkPrecisionOptions& opt, double h_direct) {
  std::vector<Rung> rungs;
  for (const auto& c : configs) {
    if (c.evaluator == "direct")
      for (double m : opt.direct_steps) rungs.push_back({c, opt.direct_rtol, m * h_direct});
    else
      for (double r : opt.rtols) rungs.push_back({c, r, NAN});
  }
  return rungs;
}

}  // namespace work_precision_plan_impl

/// The soe fit tolerance follows rtol (within what the fit supports), so that one knob sets the accuracy.
double Rung::history_tol() const {
  return cfg.evaluator == "soe" || cfg.evaluator == "soe-step" ? std::clamp(rtol, 1e-10, 1e-3) : NAN;
}

WorkPrecisionPlan plan_work_precision(Scene base, const WorkPrecisionOptions& opt) {
  using namespace work_precision_plan_impl;
  check_work_precision_options(opt);
  if (opt.add_history) {
    if (!base.fluid) throw InputError(base.path, "fluid", "--add-history needs a [fluid] table");
    base.effects.insert(Effect::history);
  }
  WorkPrecisionPlan plan;
  plan.opt = opt;
  plan.history = base.has(Effect::history);
  plan.collision = base.has_target();
  const std::vector<std::string> evaluators = evaluators_for(opt, plan.history);
  plan.configs = configs_for(evaluators, opt, plan.skipped);
  plan.ref_cfg = {"cvode-dense", plan.history ? "soe" : "none"};  // the reference: run 0, the tightest settings
  plan.rungs = ladder_rungs(plan.configs, opt, direct_base_step(base, evaluators));
  plan.base = std::move(base);
  return plan;
}

}  // namespace imcol::study
