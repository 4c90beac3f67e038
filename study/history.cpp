// SPDX-License-Identifier: BSD-3-Clause
#include "study/history.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/report.hpp"

namespace imcol::study {

namespace {

/// "a, b, c": the names for a message.
std::string joined_names(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

/// The column of f_hist1 (columns.size() if the run has none).
std::size_t history_column(const RunResult& r) {
  for (std::size_t i = 0; i < r.columns.size(); ++i)
    if (r.columns[i] == "f_hist1") return i;
  return r.columns.size();
}

/// f_hist1 at the output samples (events excluded), keyed by time: the times every run shares.
std::map<double, double> force_samples(const RunResult& r) {
  std::map<double, double> m;
  const std::size_t ic = history_column(r), ie = r.columns.size() - 1;
  if (ic == r.columns.size()) return m;
  for (const auto& row : r.rows)
    if (row[ie] == 0.0) m[row[0]] = row[ic];
  return m;
}

}  // namespace

std::map<double, double> force_trace(const RunResult& r) {
  // The solver's steps near contact (RunResult::contact_rows) catch a peak faster than output.dt resolves; an event
  // keeps its value.
  std::map<double, double> m;
  const std::size_t ic = history_column(r);
  if (ic == r.columns.size()) return m;
  for (const auto* rows : {&r.rows, &r.contact_rows})
    for (const auto& row : *rows) m.emplace(row[0], row[ic]);
  return m;
}

namespace {

double peak_of(const std::map<double, double>& trace) {
  double p = 0;
  for (const auto& [t, f] : trace) p = std::max(p, std::abs(f));
  return p;
}

/// The scene with one kernel and evaluator ("none": without the history force), run; its metric and peak force.
HistoryRun run_history(const Scene& base, bool collision, const std::string& kernel, const std::string& evaluator) {
  HistoryRun r{kernel, evaluator, simulate(with_history_kernel(base, kernel, evaluator))};
  const auto& s = r.run.summary;
  r.metric = (collision ? s.e : s.u1_final_m_s).value_or(NAN);
  r.peak = peak_of(force_trace(r.run));  // the samples history_forces.csv holds
  return r;
}

/// Each row against its kernel's direct evaluation (when it ran): d_metric and d_force.
void compare_with_direct(std::vector<HistoryRun>& rows) {
  for (auto& r : rows) {
    if (r.kernel == "none") continue;
    for (const auto& ref : rows) {
      if (ref.kernel != r.kernel || ref.evaluator != "direct") continue;
      r.d_metric = std::abs(r.metric - ref.metric);
      const auto a = force_samples(r.run), b = force_samples(ref.run);
      double worst = 0;
      for (const auto& [t, f] : a)
        if (auto it = b.find(t); it != b.end()) worst = std::max(worst, std::abs(f - it->second));
      r.d_force = ref.peak > 0 ? worst / ref.peak : NAN;
    }
  }
}

}  // namespace

Scene with_history_kernel(const Scene& base, const std::string& kernel, const std::string& evaluator) {
  Scene sc = base;
  if (kernel == "none") {
    sc.effects.erase(Effect::history);
  } else {
    sc.effects.insert(Effect::history);
    sc.history.kernel = *choice_from_string<KernelKind>(kernel);
    sc.history.evaluator = *choice_from_string<HistoryEvaluator>(evaluator);
  }
  return sc;
}

void check_history_choices(const std::vector<std::string>& kernels, const std::vector<std::string>& evaluators) {
  for (const auto& k : kernels)
    if (!choice_from_string<KernelKind>(k))
      throw InputError("--kernels", k, "unknown kernel (expected " + joined_names(choice_names<KernelKind>()) + ")");
  for (const auto& e : evaluators)
    if (!choice_from_string<HistoryEvaluator>(e)) throw InputError("--evaluators", e, "unknown evaluator (expected soe, soe-step, direct)");
}

HistoryResult compare_history(const Scene& base, const std::vector<std::string>& kernels, const std::vector<std::string>& evaluators,
                              const Hooks& hooks) {
  if (!base.fluid) throw InputError(base.path, "fluid", "the history force needs a [fluid] table");
  check_history_choices(kernels, evaluators);
  HistoryResult r;
  r.collision = base.has_target();
  std::vector<std::pair<std::string, std::string>> runs = {{"none", "-"}};
  for (const auto& k : kernels)
    for (const auto& e : evaluators) runs.emplace_back(k, e);
  WorkScope scope(run_control(hooks));  // a stop request ends the run in flight; its row is dropped
  for (const auto& [k, e] : runs) {
    if ((r.cancelled = hooks.cancel_requested())) break;
    try {
      r.rows.push_back(run_history(base, r.collision, k, e));
    } catch (const Interrupted&) {
      r.cancelled = true;
      break;
    }
    if (hooks.progress) hooks.progress(r.rows.size(), runs.size());
  }
  compare_with_direct(r.rows);  // reference of each kernel: its direct evaluation
  return r;
}

Table history_table(const HistoryResult& res) {
  Table t;
  t.rows = res.rows.size();
  auto& kernel = t.add("kernel", true);
  auto& evaluator = t.add("evaluator", true);
  auto& metric = t.add(res.collision ? "e" : "u_end_m_s");
  auto& d_none = t.add("diff_from_none");
  auto& peak = t.add("peak_history_force_N");
  auto& d_ref = t.add("diff_from_reference");
  auto& d_force = t.add("force_diff_rel");
  auto& modes = t.add("modes");
  auto& state = t.add("state_size");
  auto& steps = t.add("steps");
  auto& rhs = t.add("rhs_evals");
  auto& solver = t.add("linear_solver", true);
  auto& wall = t.add("wall_time_s");
  auto& setup = t.add("setup_time_s");
  const double none_metric = res.rows.empty() ? NAN : res.rows.front().metric;
  for (const auto& r : res.rows) {
    const auto& s = r.run.summary;
    const SolverStats& sol = s.solver.stats;
    kernel.text.push_back(r.kernel), evaluator.text.push_back(r.evaluator);
    metric.numbers.push_back(r.metric), d_none.numbers.push_back(r.metric - none_metric), peak.numbers.push_back(r.peak);
    d_ref.numbers.push_back(r.d_metric), d_force.numbers.push_back(r.d_force);
    modes.numbers.push_back(s.history && s.history->modes ? static_cast<double>(*s.history->modes) : NAN);
    state.numbers.push_back(static_cast<double>(sol.state_size)), steps.numbers.push_back(static_cast<double>(sol.steps));
    rhs.numbers.push_back(static_cast<double>(sol.rhs_evals)), solver.text.push_back(sol.linear_solver);
    wall.numbers.push_back(s.wall_time_s), setup.numbers.push_back(s.setup_time_s);
  }
  return t;
}

}  // namespace imcol::study
