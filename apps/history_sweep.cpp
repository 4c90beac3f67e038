// SPDX-License-Identifier: BSD-3-Clause
#include "apps/history_sweep.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "apps/format.hpp"
#include "apps/output_unit.hpp"
#include "study/history_sweep.hpp"
#include "study/parallel_runs.hpp"
#include "apps/plot.hpp"
#include "apps/table_csv.hpp"
#include "core/errors.hpp"
#include "core/work_scope.hpp"
#include "core/report.hpp"
#include "core/timing.hpp"
#include "run/summary_json.hpp"
#include "run/progress_estimate.hpp"
#include "run/simulate.hpp"
#include "run/json_util.hpp"

namespace imcol {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

using study::HistoryCell;
using study::HistorySeries;

std::optional<double> if_ok(const HistoryCell& c, const std::optional<double>& v) { return c.ok() ? v : std::nullopt; }

/// Runs every cell on `jobs` threads (a failed run ends that cell only); a progress line on a terminal.
double run_cells(const std::vector<Scene>& scenes, const std::vector<double>& values, const std::vector<HistorySeries>& series,
                 const SweepOptions& sw, int jobs, study::HistorySweepResult& result) {
  const bool tty = sw.progress && isatty(STDERR_FILENO);
  std::size_t finished = 0, failed = 0;
  const std::size_t total = values.size() * series.size();
  const auto start = WallClock::now();
  run::ProgressTimer timer;
  auto taken = [&](std::size_t, const HistoryCell& c) {
    ++finished;
    if (!c.ok()) ++failed;
    const auto p = timer.at(static_cast<double>(finished), static_cast<double>(total));
    if (tty)
      std::cerr << "\r  history sweep: " << finished << "/" << total << " runs, " << failed << " failed, " << std::fixed
                << std::setprecision(1) << seconds_since(start) << " s, ~" << (p ? p->eta_s : 0.0) << " s left   "
                << std::defaultfloat << std::flush;
  };
  result = study::history_sweep(scenes, sw.vary, values, series, study::threads(jobs), {}, taken);
  this_thread_work().stop.throw_if_requested();  // Ctrl-C: nothing printed or kept of a stopped study
  if (tty) std::cerr << "\n";
  return seconds_since(start);
}

std::string cell_text(const std::optional<double>& v, int p) { return v && std::isfinite(*v) ? fixed(*v, p) : std::string("-"); }

/// The table: a line per point with St (of the first series that measured it) and e of each series.
void print_table(const std::vector<HistoryCell>& cells, const std::vector<HistorySeries>& series, const std::vector<double>& values,
                 const char* column) {
  std::cout << std::setw(14) << column << std::setw(9) << "St";
  for (const auto& s : series) std::cout << std::setw(std::max<int>(11, static_cast<int>(s.name().size()) + 3)) << s.name();
  std::cout << "\n";
  const std::size_t n = series.size();
  for (std::size_t i = 0; i < values.size(); ++i) {
    const HistoryCell* at = &cells[i * n];
    std::optional<double> St;
    for (std::size_t k = 0; k < n && !St; ++k) St = if_ok(at[k], at[k].summary.St);
    std::cout << std::setw(14) << std::setprecision(5) << std::defaultfloat << values[i] << std::setw(9) << cell_text(St, 2);
    for (std::size_t k = 0; k < n; ++k)
      std::cout << std::setw(std::max<int>(11, static_cast<int>(series[k].name().size()) + 3))
                << (at[k].ok() ? cell_text(at[k].summary.e, 6) : std::string("FAILED"));
    std::cout << "\n";
  }
}

/// history_sweep.json, all but its `run` block.
Json sweep_json(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base, const SweepOptions& sw,
                const char* column, const std::vector<HistorySeries>& series, const std::vector<HistoryCell>& cells, int jobs, double wall) {
  Json j = scene_json(scene_path, overrides, base);
  put_sweep_settings(j, sw, column);
  j["jobs"] = jobs;
  j["wall_time_s"] = wall;
  Json js = Json::array();
  for (const auto& s : series) js.push_back({{"kernel", s.kernel}, {"evaluator", s.evaluator}});
  j["series"] = js;
  const HistoryCell* first = nullptr;
  for (const auto& c : cells)
    if (c.ok() && !first) first = &c;
  j["e_is"] = first ? Json(to_string(first->summary.e_is)) : Json(nullptr);
  j["St_convention"] = first ? Json(first->summary.St_convention) : Json(nullptr);
  j["e_dry"] = first && first->summary.contact ? Json(first->summary.contact->e_dry) : Json(nullptr);
  Json failures = Json::array();
  for (const auto& c : cells)
    if (!c.ok())
      failures.push_back({{"point", c.point}, {"value", c.value}, {"kernel", c.series.kernel}, {"evaluator", c.series.evaluator},
                          {"reason", c.message}});
  j["failures"] = failures;
  Json rows = Json::array();
  for (const auto& c : cells) {
    const auto& s = c.summary;
    rows.push_back({{"point", c.point}, {"value", c.value}, {"kernel", c.series.kernel}, {"evaluator", c.series.evaluator},
                    {"status", c.status}, {"St", run::finite_or_null(if_ok(c, s.St))}, {"e", run::finite_or_null(if_ok(c, s.e))},
                    {"message", c.message.empty() ? Json(nullptr) : Json(c.message)}});
  }
  j["rows"] = rows;
  return j;
}

}  // namespace

namespace {

/// The opening line, the table and the runs without e; returns the number of failed runs.
int report_cells(const Scene& base, const SweepOptions& sw, const study::HistorySweepResult& res, int jobs, double wall) {
  const auto& cells = res.cells;
  const HistoryCell* first = nullptr;
  for (const auto& c : cells)
    if (c.ok() && !first) first = &c;
  std::cout << "scene " << base.name << ": e per history kernel at " << sw.points << " points of " << sw.vary << " from " << sw.from
            << " to " << sw.to << " (" << sw.spacing << " spacing, " << cells.size() << " runs on " << jobs << (jobs == 1 ? " job, " : " jobs, ")
            << std::fixed << std::setprecision(2) << wall << " s); e = " << to_string(first ? first->summary.e_is : base.measure.e)
            << std::defaultfloat << "\n";
  print_table(cells, res.series, res.values, res.column.c_str());
  int failed = 0;
  for (const auto& c : cells) {
    if (c.ok() && c.summary.e) continue;
    failed += c.ok() ? 0 : 1;
    std::cout << (c.ok() ? "no e: " : "failed: ") << c.series.name() << " at " << sw.vary << " = " << std::setprecision(5) << c.value
              << ": " << c.message << "\n";
  }
  return failed;
}

}  // namespace

int history_sweep(const std::string& scene_path, const std::vector<Override>& overrides, const HistoryCompareOptions& opt) {
  const SweepOptions& sw = opt.sweep;
  const char* column = sweep_column(sw.vary);
  if (!column) throw InputError("command line", "--vary", "unknown quantity '" + sw.vary + "' (expected velocity, viscosity, diameter, density)");
  if (sw.points > 1 && sw.from == sw.to) throw InputError("command line", "--to", "equals --from: a sweep of several points needs a range");
  check_history_choices(opt);
  const Scene base = load_scene(scene_path, overrides);
  if (!base.fluid) throw InputError(scene_path, "fluid", "the history force needs a [fluid] table");
  if (!base.has_target())
    throw InputError(base.path, "wall", "a free sphere has no collision, so no e to compare (add a [wall] or a second [[sphere]])");

  const std::vector<double> values = sweep_values(sw);
  const std::vector<Scene> scenes = sweep_scenes(scene_path, overrides, base, sw.vary, values);  // all checked before anything runs
  // The scene's own evaluator unless --evaluators was given.
  const std::vector<HistorySeries> series = study::history_series(opt.kernels, opt.evaluators_given ? opt.evaluators : std::vector<std::string>{}, base);
  OutputUnit unit(opt.out, fs::path("out") / (base.name + "-history_" + sw.vary), base.path);

  const int jobs = study::job_count(sw.jobs, values.size() * series.size());
  study::HistorySweepResult res;
  const double wall = run_cells(scenes, values, series, sw, jobs, res);
  const int failed = report_cells(base, sw, res, jobs, wall);
  const auto& cells = res.cells;
  const bool any_ok = std::any_of(cells.begin(), cells.end(), [](const HistoryCell& c) { return c.ok(); });

  Json j = sweep_json(scene_path, overrides, base, sw, column, series, cells, jobs, wall);
  j["run"] = unit.run();
  write_file_atomic(unit.dir() / "history_sweep.csv", table_csv(study::history_sweep_table(res)));
  write_file_atomic(unit.dir() / "history_sweep.json", j.dump(2) + "\n");
  if (opt.plot && any_ok) {
    std::cout.flush();
    run_plot_script("plot_history.py", unit, "history_sweep.png");
  }
  unit.commit();
  std::cout << "wrote " << (unit.target() / "history_sweep.csv").string() << " and " << (unit.target() / "history_sweep.json").string() << "\n";
  if (failed) {
    std::cout.flush();
    std::cerr << "imcol: error: " << failed << " of " << cells.size() << " runs failed; their reasons are in "
              << (unit.target() / "history_sweep.json").string() << " (failures) and " << (unit.target() / "history_sweep.csv").string()
              << " (status, message)\n";
  }
  return failed ? 3 : 0;
}

}  // namespace imcol
