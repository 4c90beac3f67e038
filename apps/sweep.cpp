// SPDX-License-Identifier: BSD-3-Clause
#include "apps/sweep.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "apps/cluster.hpp"
#include "apps/dem_export.hpp"
#include "apps/format.hpp"
#include "core/number_text.hpp"
#include "core/work_scope.hpp"
#include "apps/output_unit.hpp"
#include "study/dem_fit.hpp"
#include "study/parallel_runs.hpp"
#include "apps/plot.hpp"
#include "apps/rank_inputs.hpp"
#include "run/summary_json.hpp"
#include "run/measured_run.hpp"
#include "run/progress_estimate.hpp"
#include "run/simulate.hpp"
#include "core/errors.hpp"
#include "core/report.hpp"
#include "core/timing.hpp"
#include "run/json_util.hpp"

namespace imcol {

namespace fs = std::filesystem;

namespace {

/// sweep.csv's header, the varied quantity's column second.
std::string csv_header(const char* column) {
  std::string h = std::string("point,") + column;
  for (const auto& c : sweep_columns()) h += std::string(",") + c.name;
  return h + "\n";
}

/// One finished point's CSV row (formatted once: the file is rewritten after every point). A failed point has
/// empty cells but its status and message.
std::string csv_row(std::size_t i, const SweepPoint& p) {
  std::ostringstream csv;
  csv << i << "," << std::setprecision(12) << p.value;
  for (const auto& c : sweep_columns()) {
    csv << ",";
    if (c.number) {
      csv << csv_cell(c.number(p));
      continue;
    }
    std::string w = c.word(p);
    for (char& ch : w)
      if (ch == ',' || ch == '\n') ch = ';';
    csv << w;
  }
  csv << "\n";
  return csv.str();
}

std::string sweep_csv(const std::vector<std::string>& rows, const char* column) {
  std::string out = csv_header(column);
  for (const auto& row : rows) out += row;
  return out;
}

void check_options(const SweepOptions& opt) {
  if (!(opt.from > 0 && std::isfinite(opt.from))) throw InputError("--from", "from", "must be a positive number");
  if (!(opt.to > 0 && std::isfinite(opt.to))) throw InputError("--to", "to", "must be a positive number");
  if (opt.points < 1 || opt.points > 100000) throw InputError("--points", "points", "must lie in [1, 100000]");
  if (opt.points > 1 && opt.from == opt.to) throw InputError("--to", "to", "equals --from: a sweep of several points needs a range");
  if (opt.spacing != "log" && opt.spacing != "linear") throw InputError("--spacing", opt.spacing, "expected log or linear");
  if (opt.jobs < 0) throw InputError("--jobs", "jobs", "must be >= 0 (0 = all cores)");
  if (!opt.export_format.empty() && opt.export_format != "dem") throw InputError("command line", "--export", "unknown value '" + opt.export_format + "' (expected dem)");
  if (opt.export_format == "dem" && opt.points < 3)
    throw InputError("command line", "--export", "dem fits e_dry and St_c: it needs --points 3 or more (" + std::to_string(opt.points) + " given)");
}

struct Tally {
  int finished = 0, failed = 0;
  double wall = 0;
  std::string write_error;  // the first failed write of sweep.csv: the sweep stops taking points and reports it
  std::vector<int> points_by_rank;  // over an MPI job: the points each rank ran
  double take_s = 0, csv_write_s = 0;  // rank 0's time taking points in (decoding, sweep.csv), and writing sweep.csv
  int csv_writes = 0;
  double bytes = 0;  // the points' results as sent to rank 0
};

/// Rewrites `file` with the rows so far; a failed write is kept in the tally (the sweep then stops taking points).
void rewrite_csv(const fs::path& file, const std::string& text, Tally& tally) {
  const auto t0 = WallClock::now();
  try {
    write_file_atomic(file, text);
  } catch (const std::exception& e) {  // a full disk, a vanished folder: not a crash of the worker thread
    tally.write_error = e.what();
  }
  tally.csv_write_s += seconds_since(t0);
  ++tally.csv_writes;
}

void print_progress(const SweepOptions& opt, const Tally& tally, double t, const std::optional<run::Progress>& p) {
  std::cerr << "\r  sweep " << opt.vary << ": " << tally.finished << "/" << opt.points << " done, " << tally.failed << " failed, "
            << std::fixed << std::setprecision(1) << t << " s, ~" << (p ? p->eta_s : 0.0) << " s left   " << std::flush;
}

/// This process's threads, or the MPI job's ranks (every point, rank 0's own too, then travels as bytes): the ranks
/// that ran the points, the bytes they sent and rank 0's time taking them in go into the tally.
study::Executor sweep_executor(int jobs, Tally& tally) {
  if (cluster::world().size == 1) return study::threads(jobs);
  return cluster_executor(jobs, [&tally](int rank, std::size_t bytes, double seconds) {
    ++tally.points_by_rank[static_cast<std::size_t>(rank)];
    tally.bytes += static_cast<double>(bytes);
    tally.take_s += seconds;
  });
}

/// Runs the points on `jobs` threads (each rank's, under mpirun), rewriting dir/sweep.csv as they finish.
Tally run_points(const std::vector<Scene>& scenes, const std::vector<double>& values, study::SweepResult& result, const SweepOptions& opt,
                 const char* column, const fs::path& dir, int jobs) {
  const bool tty = opt.progress && isatty(STDERR_FILENO);
  Tally tally;
  tally.points_by_rank.assign(static_cast<std::size_t>(cluster::world().size), 0);
  std::vector<std::string> rows(values.size());  // CSV rows of the finished points, formatted once
  double last_write = -1;
  const auto start = WallClock::now();
  auto elapsed = [&] { return seconds_since(start); };
  run::ProgressTimer timer;
  auto taken = [&](std::size_t i, const study::SweepResult& r) {
    rows[i] = csv_row(i, r.points[i]);
    ++tally.finished;
    if (!r.points[i].ok) ++tally.failed;
    // Finished points survive what follows: the file is rewritten at most every 0.25 s, and at the end.
    if (tally.write_error.empty() && (tally.finished == opt.points || elapsed() - last_write >= 0.25)) {
      rewrite_csv(dir / "sweep.csv", sweep_csv(rows, column), tally);
      last_write = elapsed();
    }
    if (tty) print_progress(opt, tally, elapsed(), timer.at(tally.finished, opt.points));
    return tally.write_error.empty();  // a failed write stops the sweep taking points
  };
  result = study::run_sweep(scenes, opt.vary, values, sweep_executor(jobs, tally), {}, taken);
  this_thread_work().stop.throw_if_requested();  // Ctrl-C: nothing printed or kept of a stopped study
  tally.wall = elapsed();
  if (tty) std::cerr << "\n";
  return tally;
}

/// The table of points on stdout; the failures (for sweep.json) and the integration time of the points that ran.
nlohmann::ordered_json print_points(const std::vector<SweepPoint>& pts, const SweepOptions& opt, const char* column,
                                    const std::string& scene_name, int jobs, double& cpu) {
  std::cout << "scene " << scene_name << ": sweep of " << opt.vary << " from " << opt.from << " to " << opt.to << " (" << opt.points
            << " points, " << opt.spacing << " spacing, " << jobs << (jobs == 1 ? " job" : " jobs")
            << (cluster::world().size > 1 ? " on each of " + std::to_string(cluster::world().size) + " ranks" : std::string()) << ")\n";
  std::cout << std::setw(14) << column << std::setw(10) << "St" << std::setw(9) << "Re" << std::setw(9) << "e" << std::setw(9)
            << "steps" << std::setw(10) << "ms" << "  note\n";
  nlohmann::ordered_json failures = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto& p = pts[i];
    const auto& s = p.summary;
    auto num = [&](const std::optional<double>& v, int prec) { return p.ok && v ? fixed(*v, prec) : std::string("-"); };
    std::cout << std::setw(14) << std::setprecision(5) << std::defaultfloat << p.value << std::setw(10) << num(s.St, 2) << std::setw(9)
              << num(s.Re, 1) << std::setw(9) << num(s.e, 4) << std::setw(9)
              << (p.ok ? std::to_string(s.solver.stats.steps) : "-") << std::setw(10)
              << (p.ok ? fixed(1e3 * s.wall_time_s, 3) : "-") << "  " << (p.ok ? p.message : "FAILED: " + p.message) << "\n";
    if (p.ok) cpu += s.wall_time_s;
    if (!p.ok) failures.push_back({{"point", i}, {"value", p.value}, {"reason", p.message}});
  }
  return failures;
}

struct EStatusCounts {
  int missing = 0, disagree = 0;
  std::map<std::string, int> disagreeing;  // measure name: points where it disagrees with e
};

/// Where e is not measured, and where the named measures disagree with it (docs/bounces.md): one closing line
/// (e_status in sweep.csv; each point's message says why).
EStatusCounts report_e_status(const std::vector<SweepPoint>& pts, const Scene& base, int ok) {
  EStatusCounts c;
  std::map<std::string, int>& disagreeing = c.disagreeing;
  int& n_disagree = c.disagree;
  int& n_missing = c.missing;
  for (const auto& p : pts) {
    if (!p.ok) continue;
    const std::string st = study::e_status(p.summary);
    if (st == "not_measured") ++n_missing;
    if (st != "measures_disagree") continue;
    ++n_disagree;
    for (const auto& [k, v] : p.summary.measures_disagree) ++disagreeing[k];
  }
  if (n_missing) std::cout << "e not measured at " << n_missing << " of " << ok << " points (e_status = not_measured)";
  if (n_disagree) {
    std::cout << (n_missing ? "; " : "") << "named measures disagree with e (" << to_string(base.measure.e) << ") by more than measure.disagreement at "
              << n_disagree << " of " << ok << " points:";
    for (auto it = disagreeing.begin(); it != disagreeing.end(); ++it) std::cout << (it == disagreeing.begin() ? " " : ", ") << it->first << " (" << it->second << ")";
  }
  if (n_missing || n_disagree) std::cout << " (docs/bounces.md)\n";
  return c;
}

/// A sweep stopped by a failed write of sweep.csv: keeps what finished beside the output folder (marked by
/// sweep.partial), leaves the folder's previous content as it was, and throws.
[[noreturn]] void stop_on_write_error(OutputUnit& unit, const Tally& tally, const SweepOptions& opt) {
  std::string kept;
  try {
    kept = "the points finished so far are in " + unit.keep_beside().string() + " (sweep.partial marks them as incomplete); " +
           unit.target().string() + " is as it was";
  } catch (const std::exception& e) {
    kept = "the points finished so far could not be kept either (" + std::string(e.what()) + ")";
  }
  throw std::runtime_error("sweep stopped after " + std::to_string(tally.finished) + " of " + std::to_string(opt.points) +
                           " points: writing sweep.csv failed (" + tally.write_error + "); " + kept);
}

/// What the finished sweep found, for its closing lines and sweep.json.
struct Outcome {
  int jobs = 0, ok = 0;
  double scenes_check_s = 0;  // loading and checking every point's scene
  Tally tally;
  nlohmann::ordered_json failures;
  EStatusCounts counts;
};

/// The table, the throughput and the failures on stdout, and the e_status line.
Outcome report_points(const std::vector<SweepPoint>& pts, const SweepOptions& opt, const char* column, const Scene& base, int jobs,
                      const Tally& tally) {
  Outcome out;
  out.jobs = jobs;
  out.tally = tally;
  const double wall = tally.wall;
  double cpu = 0;
  out.failures = print_points(pts, opt, column, base.name, jobs, cpu);
  const int ok = opt.points - tally.failed;
  out.ok = ok;
  std::cout << ok << " of " << opt.points << " points ran in " << std::fixed << std::setprecision(2) << wall << " s on " << jobs
            << (jobs == 1 ? " job: " : " jobs: ") << std::setprecision(1) << ok / wall << " collisions per second (" << std::setprecision(3)
            << (ok ? 1e3 * cpu / ok : NAN) << " ms integration per point)\n";
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (!pts[i].ok) std::cout << "failed: point " << i << " (" << opt.vary << " = " << run::Json(pts[i].value) << "): " << pts[i].message << "\n";
  out.counts = report_e_status(pts, base, ok);
  return out;
}

/// sweep.json, all but its `run` block.
nlohmann::ordered_json sweep_json(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                                  const SweepOptions& opt, const char* column, const std::vector<SweepPoint>& pts, const Outcome& out) {
  nlohmann::ordered_json j;
  j["scene"] = base.name;
  j["scene_file"] = scene_path;
  nlohmann::ordered_json ov = nlohmann::ordered_json::object();  // --set/--rtol/... as given, before the varied quantity's
  for (const auto& o : overrides) ov[o.key] = o.value;
  j["overrides"] = ov;
  j["configuration"] = base.two_spheres() ? "sphere-sphere" : (base.wall ? "sphere-wall" : "free sphere");
  j["vary"] = opt.vary;
  j["column"] = column;
  j["from"] = opt.from;
  j["to"] = opt.to;
  j["points"] = opt.points;
  j["spacing"] = opt.spacing;
  j["jobs"] = out.jobs;  // threads per rank
  if (const int ranks = cluster::world().size; ranks > 1) {
    j["ranks"] = ranks;
    j["points_by_rank"] = out.tally.points_by_rank;
    // What rank 0 spends on each point beyond running its own (docs/cluster.md, "Scaling"): taking it in (decoding,
    // rewriting sweep.csv), the rewrites alone, the result's size; and loading and checking every scene at the start.
    const Tally& t = out.tally;
    j["rank0_ms_per_point"] = run::finite_or_null(1e3 * t.take_s / std::max(1, t.finished));
    j["bytes_per_point"] = run::finite_or_null(t.bytes / std::max(1, t.finished));
    j["csv_rewrites"] = t.csv_writes;
    j["csv_rewrite_ms"] = run::finite_or_null(1e3 * t.csv_write_s / std::max(1, t.csv_writes));
    j["scenes_check_s"] = out.scenes_check_s;
  }
  j["wall_time_s"] = out.tally.wall;
  j["collisions_per_second"] = run::finite_or_null(out.ok / out.tally.wall);
  j["failures"] = out.failures;
  // The first point that ran says what every point shares (a failed first point says nothing).
  const auto ran = std::find_if(pts.begin(), pts.end(), [](const SweepPoint& p) { return p.ok; });
  j["St_convention"] = ran == pts.end() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(ran->summary.St_convention);
  if (ran != pts.end()) {
    j["effects"] = effects_to_json(ran->summary.effects);
    j["e_is"] = to_string(ran->summary.e_is);
    if (ran->summary.contact) j["e_dry"] = ran->summary.contact->e_dry;  // the swept quantities (velocity, viscosity, diameter, density) leave it unchanged
  }
  j["e_not_measured_points"] = out.counts.missing;
  j["measures_disagree_points"] = out.counts.disagree;
  j["measures_disagree_counts"] = out.counts.disagreeing;
  j["complete"] = true;  // every point ran (or failed with its reason)
  if (!opt.export_format.empty()) j["export"] = opt.export_format + ".json";
  return j;
}

}  // namespace

namespace {

/// What the sweep ran on: its scene, every point's, and the threads per rank.
struct SweepInputs {
  std::string scene_path;
  std::vector<Override> overrides;
  Scene base;
  const char* column = nullptr;
  int jobs = 0;
  double scenes_check_s = 0;
};

/// The table and closing lines, sweep.json, the export and the plot; the folder swapped in. Returns the exit status.
int finish_sweep(const SweepInputs& in, const SweepOptions& opt, OutputUnit& unit, const study::SweepResult& result, const Tally& tally) {
  const fs::path& dir = unit.dir();
  const std::vector<SweepPoint>& pts = result.points;
  Outcome outcome = report_points(pts, opt, in.column, in.base, in.jobs, tally);
  outcome.scenes_check_s = in.scenes_check_s;
  nlohmann::ordered_json j = sweep_json(in.scene_path, in.overrides, in.base, opt, in.column, pts, outcome);
  j["run"] = unit.run();
  write_file_atomic(dir / "sweep.json", j.dump(2) + "\n");
  fs::remove(dir / "sweep.partial");
  std::string dem_line;
  if (opt.export_format == "dem") {
    // The scene's e_dry: the first point that ran says it (the swept quantities leave it unchanged).
    const auto ran = std::find_if(pts.begin(), pts.end(), [](const SweepPoint& p) { return p.ok; });
    const std::optional<double> e_dry =
        ran != pts.end() && ran->summary.contact ? std::optional<double>(ran->summary.contact->e_dry) : std::nullopt;
    dem_line = export_dem(dir, in.base, {in.scene_path, opt.vary, in.column, e_dry}, study::dem_points(result));
  }
  if (opt.plot) run_plot_script("plot_sweep.py", unit, "sweep.png");
  unit.commit();
  if (!dem_line.empty()) std::cout << dem_line << "\n";
  std::cout << "wrote " << (unit.target() / "sweep.csv").string() << " and " << (unit.target() / "sweep.json").string()
            << (dem_line.empty() ? "" : ", dem.csv, dem_table.csv, dem.json") << "\n";
  const int failed = tally.failed;
  if (failed) {  // stdout may go to a file or a pipe: the failure is also said where errors go
    std::cout.flush();
    std::cerr << "imcol: error: " << failed << " of " << opt.points << " sweep points failed; their reasons are in "
              << (unit.target() / "sweep.json").string() << " (failures) and " << (unit.target() / "sweep.csv").string() << " (status, message)\n";
  }
  return failed ? 3 : 0;
}

}  // namespace

int sweep(const std::string& scene_path, const std::vector<Override>& overrides, const SweepOptions& opt) {
  const char* column = sweep_column(opt.vary);
  if (!column) throw InputError("--vary", opt.vary, "unknown quantity (expected velocity, viscosity, diameter, density)");
  check_options(opt);

  SweepInputs in{scene_path, overrides, load_scene(scene_path, overrides), column};
  const std::vector<double> values = sweep_values(opt);
  const auto t_scenes = WallClock::now();
  const std::vector<Scene> scenes = sweep_scenes(scene_path, overrides, in.base, opt.vary, values);
  in.scenes_check_s = seconds_since(t_scenes);
  in.jobs = study::job_count(opt.jobs, values.size());
  // The folder is one unit (apps/output_unit.hpp): the sweep is built beside it and swapped in when complete.
  // sweep.partial marks sweep.csv as incomplete until then; a sweep stopped by a write error keeps both beside the folder.
  // Under mpirun, rank 0 alone takes the folder, writes and prints; a refused folder ends every rank.
  if (const int differ = cluster::agree(sweep_inputs(scenes, opt))) return differ;  // ranks on other inputs: refused
  std::optional<OutputUnit> unit;
  const int refused = cluster::on_rank0([&] {
    unit.emplace(opt.out, fs::path("out") / (in.base.name + "-sweep_" + opt.vary), in.base.path);
    write_file_atomic(unit->dir() / "sweep.partial",
                      "sweep in progress or interrupted (pid " + std::to_string(::getpid()) +
                          "): sweep.csv holds only the points finished so far; a complete sweep removes this file and writes sweep.json\n");
  });
  if (refused) return refused;
  // Under mpirun, ranks > 0 run points for rank 0 (docs/cluster.md).
  if (cluster::world().rank > 0) {
    study::run_sweep(scenes, opt.vary, values, cluster_executor(in.jobs));
    return 0;
  }
  study::SweepResult result;
  const Tally tally = run_points(scenes, values, result, opt, column, unit->dir(), in.jobs);
  if (!tally.write_error.empty()) stop_on_write_error(*unit, tally, opt);
  return finish_sweep(in, opt, *unit, result, tally);
}

nlohmann::ordered_json scene_json(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base) {
  nlohmann::ordered_json j;
  j["scene"] = base.name;
  j["scene_file"] = scene_path;
  nlohmann::ordered_json ov = nlohmann::ordered_json::object();  // --set/--rtol/... as given
  for (const auto& o : overrides) ov[o.key] = o.value;
  j["overrides"] = ov;
  j["configuration"] = base.two_spheres() ? "sphere-sphere" : (base.wall ? "sphere-wall" : "free sphere");
  return j;
}

void put_sweep_settings(nlohmann::ordered_json& j, const study::SweepRange& opt, const char* column) {
  j["vary"] = opt.vary;
  j["column"] = column;
  j["from"] = opt.from;
  j["to"] = opt.to;
  j["points"] = opt.points;
  j["spacing"] = opt.spacing;
}

}  // namespace imcol
