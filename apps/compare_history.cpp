// SPDX-License-Identifier: BSD-3-Clause
#include "apps/compare_history.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "apps/format.hpp"
#include "apps/option_rules.hpp"
#include "apps/plot.hpp"
#include "run/simulate.hpp"
#include "core/errors.hpp"
#include "core/report.hpp"

namespace imcol {

namespace fs = std::filesystem;

namespace {

struct Row {
  std::string kernel, evaluator;
  RunResult run;
  double metric = NAN;         // e (collision) or final velocity (free sphere)
  double peak = 0;             // max |f_H| at the samples, N
  double d_metric = NAN;       // |metric − reference|
  double d_force = NAN;        // max |f_H − f_H,ref| / peak_ref over common samples
};

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

/// f_hist1 at every sample the run kept: the output samples, the events and the solver's steps near contact
/// (RunResult::contact_rows), where the force peaks faster than output.dt resolves. By time; an event keeps its value.
std::map<double, double> force_trace(const RunResult& r) {
  std::map<double, double> m;
  const std::size_t ic = history_column(r);
  if (ic == r.columns.size()) return m;
  for (const auto* rows : {&r.rows, &r.contact_rows})
    for (const auto& row : *rows) m.emplace(row[0], row[ic]);
  return m;
}

double peak_of(const std::map<double, double>& trace) {
  double p = 0;
  for (const auto& [t, f] : trace) p = std::max(p, std::abs(f));
  return p;
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

void check_history_choices(const HistoryCompareOptions& opt) {
  for (const auto& k : opt.kernels)
    if (!choice_from_string<KernelKind>(k))
      throw InputError("--kernels", k, "unknown kernel (expected " + name_list(choice_names<KernelKind>()) + ")");
  for (const auto& e : opt.evaluators)
    if (!choice_from_string<HistoryEvaluator>(e)) throw InputError("--evaluators", e, "unknown evaluator (expected soe, soe-step, direct)");
}

namespace {

/// The scene with one kernel and evaluator ("none": without the history force), run; its metric and peak force.
Row run_one(const Scene& base, bool collision, const std::string& kernel, const std::string& evaluator) {
  Row r{kernel, evaluator, simulate(with_history_kernel(base, kernel, evaluator))};
  const auto& s = r.run.summary;
  r.metric = (collision ? s.e : s.u1_final_m_s).value_or(NAN);
  r.peak = peak_of(force_trace(r.run));  // the samples history_forces.csv holds
  std::cerr << "  ran " << kernel << (kernel == "none" ? "" : " / " + evaluator) << "\n";
  return r;
}

/// Each row against its kernel's direct evaluation (when it ran): d_metric and d_force.
void compare_with_direct(std::vector<Row>& rows) {
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

/// history.csv and history_forces.csv.
struct HistoryFiles {
  std::string table, forces;
};

/// The table on stdout; the same rows for history.csv, and each run's f_hist1 samples for history_forces.csv.
HistoryFiles report_rows(const std::vector<Row>& rows, bool collision, const std::string& scene_name) {
  const std::string metric_name = collision ? "e" : "u_end m/s";
  std::cout << "scene " << scene_name << ": history-force kernels and evaluators (reference: the direct evaluator of the same kernel)\n";
  std::cout << std::left << std::setw(12) << "kernel" << std::setw(8) << "eval" << std::right << std::setw(12) << metric_name
            << std::setw(10) << "d(none)" << std::setw(12) << "peak f_H1 N" << std::setw(10) << "d vs ref" << std::setw(11)
            << "dF/F_peak" << std::setw(7) << "modes" << std::setw(7) << "state" << std::setw(8) << "steps" << std::setw(9)
            << "rhs" << std::setw(10) << "wall ms" << std::setw(10) << "setup ms" << "\n";
  std::ostringstream csv;
  csv << "kernel,evaluator," << (collision ? "e" : "u_end_m_s")
      << ",diff_from_none,peak_history_force_N,diff_from_reference,force_diff_rel,modes,state_size,steps,rhs_evals,"
         "linear_solver,wall_time_s,setup_time_s\n";
  const double none_metric = rows.front().metric;
  std::ostringstream forces;
  forces << std::setprecision(10) << "label,t,f_hist1,kernel,evaluator\n";
  for (const auto& r : rows) {
    const auto& s = r.run.summary;
    const SolverStats& sol = s.solver.stats;
    const std::optional<long> hm = s.history ? s.history->modes : std::nullopt;
    const std::string modes = hm ? std::to_string(*hm) : "-";
    const double wall = s.wall_time_s, setup = s.setup_time_s;
    std::cout << std::left << std::setw(12) << r.kernel << std::setw(8) << r.evaluator << std::right << std::setw(12)
              << (std::isnan(r.metric) ? "-" : fixed(r.metric, 6)) << std::setw(10) << sci(r.metric - none_metric, 1)
              << std::setw(12) << sci(r.peak) << std::setw(10) << sci(r.d_metric, 1) << std::setw(11) << sci(r.d_force, 1)
              << std::setw(7) << modes << std::setw(7) << sol.state_size << std::setw(8)
              << sol.steps << std::setw(9) << sol.rhs_evals << std::setw(10) << std::fixed
              << std::setprecision(2) << 1e3 * wall << std::setw(10) << 1e3 * setup << "\n";
    // A value that is not there (no direct reference, no e) is an empty cell, as in the other CSV files.
    csv << r.kernel << "," << r.evaluator << "," << csv_number(r.metric) << "," << csv_number(r.metric - none_metric) << ","
        << csv_number(r.peak) << "," << csv_number(r.d_metric) << "," << csv_number(r.d_force) << ","
        << (hm ? std::to_string(*hm) : "") << "," << sol.state_size << "," << sol.steps << ","
        << sol.rhs_evals << "," << sol.linear_solver << "," << csv_number(wall) << "," << csv_number(setup) << "\n";
    if (r.kernel != "none")
      for (const auto& [t, f] : force_trace(r.run))
        forces << r.kernel << " " << r.evaluator << "," << t << "," << f << "," << r.kernel << "," << r.evaluator << "\n";
  }
  return {csv.str(), forces.str()};
}

}  // namespace

int compare_history(const std::string& scene_path, const std::vector<Override>& overrides, const HistoryCompareOptions& opt) {
  Scene base = load_scene(scene_path, overrides);
  OutputUnit unit(opt.out, fs::path("out") / (base.name + "-history"), base.path);
  if (!base.fluid) throw InputError(scene_path, "fluid", "the history force needs a [fluid] table");
  check_history_choices(opt);
  const bool collision = base.has_target();

  std::vector<Row> rows;
  rows.push_back(run_one(base, collision, "none", "-"));
  for (const auto& k : opt.kernels)
    for (const auto& e : opt.evaluators) rows.push_back(run_one(base, collision, k, e));
  compare_with_direct(rows);  // reference of each kernel: its direct evaluation

  const HistoryFiles files = report_rows(rows, collision, base.name);
  write_file_atomic(unit.dir() / "history.csv", files.table);
  write_file_atomic(unit.dir() / "history_forces.csv", files.forces);
  if (opt.plot) run_plot_script("plot_history.py", unit, "history.png");
  unit.commit();
  std::cout << "wrote " << (unit.target() / "history.csv").string() << " and " << (unit.target() / "history_forces.csv").string() << "\n";
  return 0;
}

}  // namespace imcol
