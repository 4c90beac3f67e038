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
#include "study/parallel_runs.hpp"
#include "apps/plot.hpp"
#include "core/errors.hpp"
#include "core/report.hpp"
#include "core/timing.hpp"
#include "run/simulate.hpp"
#include "run/json_util.hpp"

namespace imcol {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

/// One series of the plot: a kernel and its evaluator, or "none" (without the history force).
struct Series {
  std::string kernel, evaluator;
  std::string name() const { return kernel == "none" ? kernel : kernel + " " + evaluator; }
};

/// One run: a sweep point with one series.
struct Cell {
  int point = 0;
  double value = NAN;
  Series series;
  std::string status = "ok";  // ok | failed (the run threw: the message says why)
  std::string message;        // failed: the error; ok: why e is missing, if it is
  RunSummary summary;         // when ok
  bool ok() const { return status == "ok"; }
};

/// none, then each kernel with each evaluator: the scene's own evaluator unless --evaluators was given.
std::vector<Series> series_of(const HistoryCompareOptions& opt, const Scene& base) {
  std::vector<std::string> evaluators = opt.evaluators;
  if (!opt.evaluators_given) evaluators = {to_string(base.history.evaluator)};
  std::vector<Series> s = {{"none", "-"}};
  for (const auto& k : opt.kernels)
    for (const auto& e : evaluators)
      if (std::none_of(s.begin(), s.end(), [&](const Series& x) { return x.kernel == k && x.evaluator == e; })) s.push_back({k, e});
  return s;
}

std::optional<double> if_ok(const Cell& c, const std::optional<double>& v) { return c.ok() ? v : std::nullopt; }

/// history_sweep.csv: a row per point and series.
std::string sweep_csv(const std::vector<Cell>& cells, const char* column) {
  std::ostringstream csv;
  csv << "point," << column << ",kernel,evaluator,status,St,e,St_initial,Re,impact_speed_m_s,e_is,steps,wall_time_s,message\n";
  for (const auto& c : cells) {
    const auto& s = c.summary;
    std::string msg = c.message;
    for (char& ch : msg)
      if (ch == ',' || ch == '\n') ch = ';';
    csv << c.point << "," << csv_number(c.value) << "," << c.series.kernel << "," << c.series.evaluator << "," << c.status << ","
        << csv_cell(if_ok(c, s.St)) << "," << csv_cell(if_ok(c, s.e)) << "," << csv_cell(if_ok(c, s.St_initial)) << ","
        << csv_cell(if_ok(c, s.Re)) << "," << csv_cell(c.ok() && s.contact ? s.contact->impact_speed_m_s : std::nullopt) << ","
        << (c.ok() ? to_string(s.e_is) : "") << "," << (c.ok() ? std::to_string(s.solver.stats.steps) : "") << ","
        << (c.ok() ? csv_number(s.wall_time_s) : "") << "," << msg << "\n";
  }
  return csv.str();
}

/// Runs every cell on `jobs` threads (a failed run ends that cell only); a progress line on a terminal.
double run_cells(const std::vector<Scene>& scenes, std::vector<Cell>& cells, int jobs, bool progress) {
  const bool tty = progress && isatty(STDERR_FILENO);
  std::size_t finished = 0, failed = 0;
  const auto start = WallClock::now();
  auto run_cell = [&](std::size_t i) {
    Cell c = cells[i];
    try {
      // e needs no force columns (as imcol sweep)
      c.summary = simulate(with_history_kernel(scenes[c.point], c.series.kernel, c.series.evaluator), false, Recording::kinematics).summary;
      if (!c.summary.e) c.message = c.summary.e_missing.value_or("e is undefined");
    } catch (const std::exception& e) {
      c.status = "failed";
      c.message = e.what();
    }
    return c;
  };
  auto take = [&](std::size_t i, Cell c) {
    cells[i] = std::move(c);
    ++finished;
    if (!cells[i].ok()) ++failed;
    if (tty)
      std::cerr << "\r  history sweep: " << finished << "/" << cells.size() << " runs, " << failed << " failed, " << std::fixed
                << std::setprecision(1) << seconds_since(start) << " s   " << std::defaultfloat << std::flush;
    return true;
  };
  study::run_parallel(cells.size(), jobs, run_cell, take);
  if (tty) std::cerr << "\n";
  return seconds_since(start);
}

std::string cell_text(const std::optional<double>& v, int p) { return v && std::isfinite(*v) ? fixed(*v, p) : std::string("-"); }

/// The table: a line per point with St (of the first series that measured it) and e of each series.
void print_table(const std::vector<Cell>& cells, const std::vector<Series>& series, const std::vector<double>& values,
                 const char* column) {
  std::cout << std::setw(14) << column << std::setw(9) << "St";
  for (const auto& s : series) std::cout << std::setw(std::max<int>(11, static_cast<int>(s.name().size()) + 3)) << s.name();
  std::cout << "\n";
  const std::size_t n = series.size();
  for (std::size_t i = 0; i < values.size(); ++i) {
    const Cell* at = &cells[i * n];
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
                const char* column, const std::vector<Series>& series, const std::vector<Cell>& cells, int jobs, double wall) {
  Json j = scene_json(scene_path, overrides, base);
  put_sweep_settings(j, sw, column);
  j["jobs"] = jobs;
  j["wall_time_s"] = wall;
  Json js = Json::array();
  for (const auto& s : series) js.push_back({{"kernel", s.kernel}, {"evaluator", s.evaluator}});
  j["series"] = js;
  const Cell* first = nullptr;
  for (const auto& c : cells)
    if (c.ok() && !first) first = &c;
  j["e_is"] = first ? Json(first->summary.e_is) : Json(nullptr);
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
  const std::vector<Series> series = series_of(opt, base);
  OutputUnit unit(opt.out, fs::path("out") / (base.name + "-history_" + sw.vary), base.path);

  std::vector<Cell> cells;  // point by point, series by series
  for (std::size_t i = 0; i < values.size(); ++i)
    for (const auto& s : series) {
      Cell c;
      c.point = static_cast<int>(i);
      c.value = values[i];
      c.series = s;
      cells.push_back(std::move(c));
    }
  const int jobs = study::job_count(sw.jobs, cells.size());
  const double wall = run_cells(scenes, cells, jobs, sw.progress);

  const Cell* first = nullptr;
  for (const auto& c : cells)
    if (c.ok() && !first) first = &c;
  std::cout << "scene " << base.name << ": e per history kernel at " << sw.points << " points of " << sw.vary << " from " << sw.from
            << " to " << sw.to << " (" << sw.spacing << " spacing, " << cells.size() << " runs on " << jobs << (jobs == 1 ? " job, " : " jobs, ")
            << std::fixed << std::setprecision(2) << wall << " s); e = " << to_string(first ? first->summary.e_is : base.measure.e)
            << std::defaultfloat << "\n";
  print_table(cells, series, values, column);
  int failed = 0;
  for (const auto& c : cells) {
    if (c.ok() && c.summary.e) continue;
    failed += c.ok() ? 0 : 1;
    std::cout << (c.ok() ? "no e: " : "failed: ") << c.series.name() << " at " << sw.vary << " = " << std::setprecision(5) << c.value
              << ": " << c.message << "\n";
  }

  Json j = sweep_json(scene_path, overrides, base, sw, column, series, cells, jobs, wall);
  j["run"] = unit.run();
  write_file_atomic(unit.dir() / "history_sweep.csv", sweep_csv(cells, column));
  write_file_atomic(unit.dir() / "history_sweep.json", j.dump(2) + "\n");
  if (opt.plot && first) {
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
