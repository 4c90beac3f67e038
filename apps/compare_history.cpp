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
#include "apps/table_csv.hpp"
#include "run/simulate.hpp"
#include "core/errors.hpp"
#include "core/work_scope.hpp"
#include "core/report.hpp"

namespace imcol {

namespace fs = std::filesystem;
using study::HistoryRun;

void check_history_choices(const HistoryCompareOptions& opt) { study::check_history_choices(opt.kernels, opt.evaluators); }

namespace {

/// history.csv and history_forces.csv.
struct HistoryFiles {
  std::string table, forces;
};

/// The table on stdout; the same rows for history.csv, and each run's f_hist1 samples for history_forces.csv.
HistoryFiles report_rows(const study::HistoryResult& res, const std::string& scene_name) {
  const std::vector<HistoryRun>& rows = res.rows;
  const bool collision = res.collision;
  const std::string metric_name = collision ? "e" : "u_end m/s";
  std::cout << "scene " << scene_name << ": history-force kernels and evaluators (reference: the direct evaluator of the same kernel)\n";
  std::cout << std::left << std::setw(12) << "kernel" << std::setw(8) << "eval" << std::right << std::setw(12) << metric_name
            << std::setw(10) << "d(none)" << std::setw(12) << "peak f_H1 N" << std::setw(10) << "d vs ref" << std::setw(11)
            << "dF/F_peak" << std::setw(7) << "modes" << std::setw(7) << "state" << std::setw(8) << "steps" << std::setw(9)
            << "rhs" << std::setw(10) << "wall ms" << std::setw(10) << "setup ms" << "\n";
  const double none_metric = rows.front().metric;
  std::ostringstream forces;
  forces << std::setprecision(10) << "label,t,f_hist1,kernel,evaluator\n";
  for (const auto& r : rows) {
    const auto& s = r.run.summary;
    const SolverStats& sol = s.solver.stats;
    const std::string modes = s.history && s.history->modes ? std::to_string(*s.history->modes) : "-";
    const double wall = s.wall_time_s, setup = s.setup_time_s;
    std::cout << std::left << std::setw(12) << r.kernel << std::setw(8) << r.evaluator << std::right << std::setw(12)
              << (std::isnan(r.metric) ? "-" : fixed(r.metric, 6)) << std::setw(10) << sci(r.metric - none_metric, 1)
              << std::setw(12) << sci(r.peak) << std::setw(10) << sci(r.d_metric, 1) << std::setw(11) << sci(r.d_force, 1)
              << std::setw(7) << modes << std::setw(7) << sol.state_size << std::setw(8)
              << sol.steps << std::setw(9) << sol.rhs_evals << std::setw(10) << std::fixed
              << std::setprecision(2) << 1e3 * wall << std::setw(10) << 1e3 * setup << "\n";
    if (r.kernel != "none")
      for (const auto& [t, f] : study::force_trace(r.run))
        forces << r.kernel << " " << r.evaluator << "," << t << "," << f << "," << r.kernel << "," << r.evaluator << "\n";
  }
  return {table_csv(study::history_table(res)), forces.str()};
}

}  // namespace

int compare_history(const std::string& scene_path, const std::vector<Override>& overrides, const HistoryCompareOptions& opt) {
  Scene base = load_scene(scene_path, overrides);
  OutputUnit unit(opt.out, fs::path("out") / (base.name + "-history"), base.path);
  if (!base.fluid) throw InputError(scene_path, "fluid", "the history force needs a [fluid] table");
  check_history_choices(opt);

  study::Hooks hooks;
  std::vector<std::string> names = {"none"};  // what each run is, in the order they go
  for (const auto& k : opt.kernels)
    for (const auto& e : opt.evaluators) names.push_back(k + " / " + e);
  hooks.progress = [&](std::size_t done, std::size_t) { std::cerr << "  ran " << names[done - 1] << "\n"; };
  const study::HistoryResult res = study::compare_history(base, opt.kernels, opt.evaluators, hooks);
  this_thread_work().stop.throw_if_requested();  // Ctrl-C: nothing printed or kept of a stopped study

  const HistoryFiles files = report_rows(res, base.name);
  write_file_atomic(unit.dir() / "history.csv", files.table);
  write_file_atomic(unit.dir() / "history_forces.csv", files.forces);
  if (opt.plot) run_plot_script("plot_history.py", unit, "history.png");
  unit.commit();
  std::cout << "wrote " << (unit.target() / "history.csv").string() << " and " << (unit.target() / "history_forces.csv").string() << "\n";
  return 0;
}

}  // namespace imcol
