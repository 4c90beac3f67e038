// SPDX-License-Identifier: BSD-3-Clause
// The runs of a work-precision ladder (study/work_precision.hpp): the options checked, the integrator × evaluator
// combinations the solvers can do, and their rungs.
#include <algorithm>
#include <array>
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

constexpr std::array<LadderIntegrator, 3> kLadderIntegrators = {LadderIntegrator::cvode_dense, LadderIntegrator::cvode_gmres,
                                                                 LadderIntegrator::ida};

/// The integrators named; an unknown name is an InputError naming --integrators.
std::vector<LadderIntegrator> integrators_for(const WorkPrecisionOptions& opt) {
  std::vector<LadderIntegrator> out;
  for (const auto& i : opt.integrators) {
    const auto it = std::find_if(kLadderIntegrators.begin(), kLadderIntegrators.end(), [&](auto x) { return to_string(x) == i; });
    if (it == kLadderIntegrators.end()) throw InputError("--integrators", i, "unknown integrator (expected cvode-dense, cvode-gmres, ida)");
    out.push_back(*it);
  }
  return out;
}

/// The history evaluators to compare (all three by default where the scene has history; none without it); an
/// unknown name, or one on a scene without history, is an InputError naming --evaluators.
std::vector<std::optional<HistoryEvaluator>> evaluators_for(const WorkPrecisionOptions& opt, bool history) {
  std::vector<std::string> names = opt.evaluators;
  if (names.empty()) names = history ? std::vector<std::string>{"soe-step", "soe", "direct"} : std::vector<std::string>{"none"};
  std::vector<std::optional<HistoryEvaluator>> out;
  for (const auto& e : names) {
    const auto ev = choice_from_string<HistoryEvaluator>(e);
    if (!ev && e != "none") throw InputError("--evaluators", e, "unknown evaluator (expected soe, soe-step, direct)");
    if (ev && !history)
      throw InputError("--evaluators", e, "the scene has no history effect (list it in `effects`, or pass --add-history)");
    out.push_back(ev);
  }
  return out;
}

/// Every evaluator with every integrator; a combination the solvers cannot do goes to `skipped` with its reason.
std::vector<LadderConfig> configs_for(const std::vector<std::optional<HistoryEvaluator>>& evaluators,
                                      const std::vector<LadderIntegrator>& integrators, std::vector<std::string>& skipped) {
  std::vector<LadderConfig> configs;
  for (const auto& ev : evaluators)
    for (const auto in : integrators) {
      const LadderConfig c{in, ev};
      if (in == LadderIntegrator::cvode_gmres && ev != HistoryEvaluator::soe) {
        skipped.push_back(c.label() + ": gmres needs the memory modes of the soe history evaluator (its preconditioner)");
        continue;
      }
      configs.push_back(c);
    }
  return configs;
}

/// The direct evaluator's base step: the scene's, or the model's automatic step (read off a model built, not run).
double direct_base_step(const Scene& base, const std::vector<LadderConfig>& configs) {
  double h_direct = base.history.direct_step;
  if (std::any_of(configs.begin(), configs.end(), [](const LadderConfig& c) { return c.direct(); }) && !(h_direct > 0)) {
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
    if (c.direct())
      for (double m : opt.direct_steps) rungs.push_back({c, opt.direct_rtol, m * h_direct});
    else
      for (double r : opt.rtols) rungs.push_back({c, r, NAN});
  }
  return rungs;
}

}  // namespace work_precision_plan_impl

std::string to_string(LadderIntegrator i) {
  return i == LadderIntegrator::cvode_dense ? "cvode-dense" : i == LadderIntegrator::cvode_gmres ? "cvode-gmres" : "ida";
}

/// The soe fit tolerance follows rtol (within what the fit supports), so that one knob sets the accuracy.
double Rung::history_tol() const { return cfg.soe() ? std::clamp(rtol, 1e-10, 1e-3) : NAN; }

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
  const auto evaluators = evaluators_for(opt, plan.history);
  plan.configs = configs_for(evaluators, integrators_for(opt), plan.skipped);
  plan.ref_cfg = {LadderIntegrator::cvode_dense, std::nullopt};  // the reference: run 0, the tightest settings
  if (plan.history) plan.ref_cfg.evaluator = HistoryEvaluator::soe;
  plan.rungs = ladder_rungs(plan.configs, opt, direct_base_step(base, plan.configs));
  plan.base = std::move(base);
  return plan;
}

}  // namespace imcol::study
