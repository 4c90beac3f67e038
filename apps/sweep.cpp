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
#include "apps/output_unit.hpp"
#include "study/parallel_runs.hpp"
#include "apps/plot.hpp"
#include "apps/rank_inputs.hpp"
#include "run/measured_run.hpp"
#include "run/simulate.hpp"
#include "core/errors.hpp"
#include "core/report.hpp"
#include "core/timing.hpp"
#include "run/json_util.hpp"
#include "run/summary_json.hpp"

namespace imcol {

namespace fs = std::filesystem;

namespace {

struct Quantity {
  const char* name;
  const char* column;  // CSV column of the varied value
};

const Quantity kQuantities[] = {{"velocity", "velocity_m_s"}, {"viscosity", "viscosity_Pa_s"}, {"diameter", "diameter_m"}, {"density", "density_kg_m3"}};

const Quantity* quantity(const std::string& vary) {
  for (const auto& x : kQuantities)
    if (vary == x.name) return &x;
  return nullptr;
}

struct PointResult : SweepPoint {
  bool done = false;
  std::string row;  // CSV
};

/// What became of e at a point that ran: measured (the named measures agree within measure.disagreement),
/// measures_disagree (the message names them), or not_measured (the message says why).
std::string e_status(const RunSummary& s) {
  if (!s.e) return "not_measured";
  return s.measures_disagree.empty() ? "measured" : "measures_disagree";
}

/// sweep.csv's header, the varied quantity's column second.
std::string csv_header(const Quantity& q) {
  std::string h = std::string("point,") + q.column;
  for (const auto& c : sweep_columns()) h += std::string(",") + c.name;
  return h + "\n";
}

/// One finished point's CSV row (formatted once: the file is rewritten after every point). A failed point has
/// empty cells but its status and message.
std::string csv_row(std::size_t i, const PointResult& p) {
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

/// Runs point i and formats its CSV row.
PointResult point_result(const Scene& scene, std::size_t i, double value) {
  PointResult r;
  static_cast<SweepPoint&>(r) = run_sweep_point(scene, value);
  r.done = true;
  r.row = csv_row(i, r);
  return r;
}

/// A finished point as a worker rank sends it to rank 0 (docs/cluster.md): its CSV row as formatted where it ran, and
/// its summary, as CBOR of summary.json's object (run/summary_json.hpp): doubles keep every bit.
std::string encode_point(const PointResult& r) {
  run::Json j;
  j["ok"] = r.ok;
  j["value"] = r.value;
  j["message"] = r.message;
  j["row"] = r.row;
  if (r.ok) j["summary"] = r.summary;
  const auto v = run::Json::to_cbor(j);
  return std::string(v.begin(), v.end());
}

PointResult decode_point(const std::string& bytes) {
  const run::Json j = run::Json::from_cbor(bytes);
  PointResult r;
  r.done = true;
  r.ok = j["ok"].get<bool>();
  r.value = j["value"].get<double>();
  r.message = j["message"].get<std::string>();
  r.row = j["row"].get<std::string>();
  if (r.ok) r.summary = j["summary"].get<RunSummary>();
  return r;
}

std::string sweep_csv(const std::vector<PointResult>& pts, const Quantity& q) {
  std::string out = csv_header(q);
  for (const auto& p : pts)
    if (p.done) out += p.row;
  return out;
}

/// A point's message: why e is missing (with the hint to raise solver.t_end only where the retries with a longer t_end
/// showed that it helps: then they were kept), or which named measures disagree with e, or the t_end it took.
std::string point_message(const RunSummary& s, double t_end_scene, double t_end_run) {
  std::ostringstream os;
  os << std::setprecision(4);
  const bool extended = t_end_run != t_end_scene;
  if (!s.e) return e_missing_message(s, t_end_scene, t_end_run);
  if (extended) os << "t_end extended to " << t_end_run << " s";
  if (e_status(s) == "measures_disagree") {
    os << (extended ? "; " : "") << "measures disagree with e (" << to_string(s.e_is) << ") by more than "
       << "measure.disagreement:";
    for (const auto& [k, v] : s.measures_disagree) os << " " << k << " = " << v;
  }
  return os.str();
}

/// "sweep point 3 (velocity = 0.5)": a point in messages.
std::string point_name(std::size_t i, const std::string& vary, double value) {
  std::ostringstream os;
  os << std::setprecision(6) << "sweep point " << i << " (" << vary << " = " << value << ")";
  return os.str();
}

}  // namespace

const char* sweep_column(const std::string& vary) {
  const Quantity* q = quantity(vary);
  return q ? q->column : nullptr;
}

std::vector<std::string> sweep_quantities() {
  std::vector<std::string> out;
  for (const auto& q : kQuantities) out.emplace_back(q.name);
  return out;
}

void check_sweep_quantity(const std::string& vary, const std::string& where, const std::string& key) {
  if (quantity(vary)) return;
  std::string list;
  for (const auto& q : kQuantities) list += (list.empty() ? "" : ", ") + std::string(q.name);
  throw InputError(where, key, "unknown value '" + vary + "' (expected " + list + ")");
}

void check_sweep_values(const std::string& vary, const std::vector<double>& values, const std::string& where, const std::string& key) {
  if (values.empty() || values.size() > 100000)
    throw InputError(where, key, "must hold 1 to 100000 values (" + std::to_string(values.size()) + " given)");
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!(values[i] > 0 && std::isfinite(values[i]))) throw InputError(where, key, point_name(i, vary, values[i]) + ": must be a positive number");
}

const std::vector<SweepColumn>& sweep_columns() {
  using P = const SweepPoint&;
  using V = std::optional<double>;
  // A failed point has no numbers.
  static const std::vector<SweepColumn> cols = {
      {"St", [](P p) { return p.ok ? p.summary.St : V(); }, nullptr},
      {"St_B_table_6_1", [](P p) { return p.ok ? p.summary.St_B_table_6_1 : V(); }, nullptr},
      {"St_B_eq_6_2", [](P p) { return p.ok ? p.summary.St_B_eq_6_2 : V(); }, nullptr},
      {"St_L", [](P p) { return p.ok ? p.summary.St_L : V(); }, nullptr},
      {"St_initial", [](P p) { return p.ok ? p.summary.St_initial : V(); }, nullptr},
      {"Re", [](P p) { return p.ok ? p.summary.Re : V(); }, nullptr},
      {"e", [](P p) { return p.ok ? p.summary.e : V(); }, nullptr},
      {"e_instant", [](P p) { return p.ok ? p.summary.e_instant : V(); }, nullptr},
      // The named measures of e (docs/bounces.md); `e` is the one e_is names (measure.e).
      {"e_fit_distance", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::fit_distance) : V(); }, nullptr},
      {"e_at_gap", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::at_gap) : V(); }, nullptr},
      {"e_peak_rebound", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::peak_rebound) : V(); }, nullptr},
      {"separated", [](P p) { return p.ok ? V(p.summary.separated ? 1.0 : 0.0) : V(); }, nullptr},
      {"min_gap_m", [](P p) { return p.ok ? p.summary.min_gap_m : V(); }, nullptr},
      {"steps", [](P p) { return p.ok ? V(static_cast<double>(p.summary.solver.stats.steps)) : V(); }, nullptr},
      {"rhs_evals", [](P p) { return p.ok ? V(static_cast<double>(p.summary.solver.stats.rhs_evals)) : V(); }, nullptr},
      {"wall_time_s", [](P p) { return p.ok ? V(p.summary.wall_time_s) : V(); }, nullptr},
      {"status", nullptr, [](P p) { return std::string(p.ok ? "ok" : "failed"); }},
      {"message", nullptr, [](P p) { return p.message; }},
      {"e_is", nullptr, [](P p) { return p.ok ? std::string(to_string(p.summary.e_is)) : std::string(); }},
      {"e_status", nullptr, [](P p) { return p.ok ? e_status(p.summary) : std::string(); }},
      {"e_fit_time", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::fit_time) : V(); }, nullptr},
      {"e_yang_hunt_2006", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::yang_hunt_2006) : V(); }, nullptr},
      {"e_joseph_2001", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::joseph_2001) : V(); }, nullptr},
      {"e_gondret_2002", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::gondret_2002) : V(); }, nullptr},
  };
  return cols;
}

SweepPoint run_sweep_point(const Scene& scene, double value) {
  SweepPoint r;
  r.value = value;
  try {
    // A point whose collision or rebound window did not fit in t_end is rerun with t_end doubled (twice at most).
    RunResult run = simulate_for_e(scene);
    r.summary = std::move(run.summary);
    r.ok = true;
    r.message = point_message(r.summary, scene.solver.t_end, run.scene.solver.t_end);
  } catch (const std::exception& e) {
    r.message = e.what();  // a solver failure (or anything else) ends this point only
  }
  return r;
}

std::vector<double> sweep_values(const SweepOptions& opt) {
  std::vector<double> v;
  for (int i = 0; i < opt.points; ++i) {
    const double f = opt.points == 1 ? 0.0 : static_cast<double>(i) / (opt.points - 1);
    v.push_back(opt.spacing == "log" ? opt.from * std::pow(opt.to / opt.from, f) : opt.from + f * (opt.to - opt.from));
  }
  return v;
}

std::vector<Override> sweep_overrides(const Scene& base, const std::string& vary, double value) {
  std::vector<Override> ov;
  const std::size_t n = base.spheres.size();
  const double t_end = base.solver.t_end;
  if (vary == "velocity") {
    const double v0 = base.spheres[0].velocity;
    ov.push_back({"sphere[0].velocity", toml_float(v0 < 0 ? -value : value)});
    // A slower approach takes longer: t_end grows with the time to cross the initial gap.
    if (v0 != 0 && value < std::abs(v0)) ov.push_back({"solver.t_end", toml_float(t_end * std::abs(v0) / value)});
  } else if (vary == "viscosity") {
    ov.push_back({"fluid.viscosity", toml_float(value)});
  } else if (vary == "density") {
    // Every sphere's density by the same factor: the impactor's becomes `value`, ratios are kept.
    const double s = value / base.spheres[0].density;
    for (std::size_t k = 0; k < n; ++k) ov.push_back({"sphere[" + std::to_string(k) + "].density", toml_float(base.spheres[k].density * s)});
  } else if (vary == "diameter") {
    // Every sphere scaled by the same factor (the impactor's diameter becomes `value`); the initial
    // gap keeps its size in diameters, the target (or wall) stays where it is.
    const double s = value / base.spheres[0].diameter;
    for (std::size_t k = 0; k < n; ++k)
      ov.push_back({"sphere[" + std::to_string(k) + "].diameter", toml_float(base.spheres[k].diameter * s)});
    if (base.has_target()) {
      const double a0 = base.spheres[0].diameter / 2, x0 = base.spheres[0].position;
      const double face = n == 2 ? base.spheres[1].position - base.spheres[1].diameter / 2 : base.wall->position;
      const double face_new = n == 2 ? base.spheres[1].position - s * base.spheres[1].diameter / 2 : base.wall->position;
      const double gap = face - (x0 + a0);
      ov.push_back({"sphere[0].position", toml_float(face_new - s * (gap + a0))});
    }
    if (s > 1) ov.push_back({"solver.t_end", toml_float(t_end * s)});
  } else {
    throw InputError("--vary", vary, "unknown quantity (expected velocity, viscosity, diameter, density)");
  }
  return ov;
}

std::vector<Scene> sweep_scenes(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                                const std::string& vary, const std::vector<double>& values) {
  return sweep_scenes([&](const std::vector<Override>& ov) { return load_scene(scene_path, ov); }, overrides, base, vary, values);
}

std::vector<Scene> sweep_scenes(const std::function<Scene(const std::vector<Override>&)>& load, const std::vector<Override>& overrides,
                                const Scene& base, const std::string& vary, const std::vector<double>& values) {
  if (vary == "viscosity" && !base.fluid) throw InputError(base.path, "fluid", "a viscosity sweep needs a [fluid] table");
  std::vector<Scene> scenes;
  for (std::size_t i = 0; i < values.size(); ++i) {
    auto ov = overrides;
    for (auto& o : sweep_overrides(base, vary, values[i])) ov.push_back(o);
    try {
      scenes.push_back(load(ov));
    } catch (const InputError& e) {
      // The same place and key, the point named before the problem.
      throw InputError(e.where(), e.key(), point_name(i, vary, values[i]) + ": " + e.problem());
    }
  }
  return scenes;
}

namespace {

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

/// The points as the DEM export reads them (apps/dem_export.hpp).
std::vector<DemPoint> dem_points(const std::vector<PointResult>& pts) {
  std::vector<DemPoint> out;
  for (const auto& p : pts) {
    DemPoint d;
    d.value = p.value;
    d.ok = p.ok;
    if (p.ok) {
      const auto& s = p.summary;
      d.e_status = e_status(s);
      if (s.U_i1 && s.U_i2) d.impact_speed_m_s = *s.U_i1 - *s.U_i2;
      d.St = s.St;
      d.St_B_eq_6_2 = s.St_B_eq_6_2;
      d.e = s.e;
    }
    out.push_back(d);
  }
  return out;
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

/// Runs the points on `jobs` threads, rewriting dir/sweep.csv as they finish.
Tally run_points(const std::vector<Scene>& scenes, std::vector<PointResult>& pts, const SweepOptions& opt, const Quantity& q,
                 const fs::path& dir, int jobs) {
  const bool tty = opt.progress && isatty(STDERR_FILENO);
  Tally tally;
  tally.points_by_rank.assign(static_cast<std::size_t>(cluster::world().size), 0);
  double last_write = -1;
  const auto start = WallClock::now();
  auto elapsed = [&] { return seconds_since(start); };

  auto run_point = [&](std::size_t i) { return point_result(scenes[i], i, pts[i].value); };
  auto take = [&](std::size_t i, PointResult r) {
    pts[i] = std::move(r);
    ++tally.finished;
    if (!pts[i].ok) ++tally.failed;
    // Finished points survive what follows: the file is rewritten at most every 0.25 s, and at the end.
    if (tally.write_error.empty() && (tally.finished == opt.points || elapsed() - last_write >= 0.25)) {
      const auto t0 = WallClock::now();
      try {
        write_file_atomic(dir / "sweep.csv", sweep_csv(pts, q));
      } catch (const std::exception& e) {  // a full disk, a vanished folder: not a crash of the worker thread
        tally.write_error = e.what();
      }
      tally.csv_write_s += seconds_since(t0);
      ++tally.csv_writes;
      last_write = elapsed();
    }
    if (tty) {
      const double t = elapsed();
      std::cerr << "\r  sweep " << opt.vary << ": " << tally.finished << "/" << opt.points << " done, " << tally.failed << " failed, "
                << std::fixed << std::setprecision(1) << t << " s, ~" << t / tally.finished * (opt.points - tally.finished) << " s left   "
                << std::flush;
    }
    return tally.write_error.empty();  // a failed write stops the sweep taking points
  };
  if (cluster::world().size == 1) {
    study::run_parallel(pts.size(), jobs, run_point, take);
  } else {  // over the MPI job's ranks: every point, rank 0's own too, goes through the bytes a worker sends
    cluster::run_distributed(
        pts.size(), jobs, [&](std::size_t i) { return encode_point(run_point(i)); },
        [&](std::size_t i, std::string bytes, int rank) {
          const auto t0 = WallClock::now();
          ++tally.points_by_rank[static_cast<std::size_t>(rank)];
          tally.bytes += static_cast<double>(bytes.size());
          const bool more = take(i, decode_point(bytes));
          tally.take_s += seconds_since(t0);
          return more;
        });
  }
  tally.wall = elapsed();
  if (tty) std::cerr << "\n";
  return tally;
}

/// The table of points on stdout; the failures (for sweep.json) and the integration time of the points that ran.
nlohmann::ordered_json print_points(const std::vector<PointResult>& pts, const SweepOptions& opt, const Quantity& q,
                                    const std::string& scene_name, int jobs, double& cpu) {
  std::cout << "scene " << scene_name << ": sweep of " << opt.vary << " from " << opt.from << " to " << opt.to << " (" << opt.points
            << " points, " << opt.spacing << " spacing, " << jobs << (jobs == 1 ? " job" : " jobs")
            << (cluster::world().size > 1 ? " on each of " + std::to_string(cluster::world().size) + " ranks" : std::string()) << ")\n";
  std::cout << std::setw(14) << q.column << std::setw(10) << "St" << std::setw(9) << "Re" << std::setw(9) << "e" << std::setw(9)
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
EStatusCounts report_e_status(const std::vector<PointResult>& pts, const Scene& base, int ok) {
  EStatusCounts c;
  std::map<std::string, int>& disagreeing = c.disagreeing;
  int& n_disagree = c.disagree;
  int& n_missing = c.missing;
  for (const auto& p : pts) {
    if (!p.ok) continue;
    const std::string st = e_status(p.summary);
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
Outcome report_points(const std::vector<PointResult>& pts, const SweepOptions& opt, const Quantity& q, const Scene& base, int jobs,
                      const Tally& tally) {
  Outcome out;
  out.jobs = jobs;
  out.tally = tally;
  const double wall = tally.wall;
  double cpu = 0;
  out.failures = print_points(pts, opt, q, base.name, jobs, cpu);
  const int ok = opt.points - tally.failed;
  out.ok = ok;
  std::cout << ok << " of " << opt.points << " points ran in " << std::fixed << std::setprecision(2) << wall << " s on " << jobs
            << (jobs == 1 ? " job: " : " jobs: ") << std::setprecision(1) << ok / wall << " collisions per second (" << std::setprecision(3)
            << (ok ? 1e3 * cpu / ok : NAN) << " ms integration per point)\n";
  for (const auto& f : out.failures)
    std::cout << "failed: point " << f["point"] << " (" << opt.vary << " = " << f["value"] << "): " << f["reason"].get<std::string>() << "\n";
  out.counts = report_e_status(pts, base, ok);
  return out;
}

/// sweep.json, all but its `run` block.
nlohmann::ordered_json sweep_json(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                                  const SweepOptions& opt, const Quantity& q, const std::vector<PointResult>& pts, const Outcome& out) {
  nlohmann::ordered_json j;
  j["scene"] = base.name;
  j["scene_file"] = scene_path;
  nlohmann::ordered_json ov = nlohmann::ordered_json::object();  // --set/--rtol/... as given, before the varied quantity's
  for (const auto& o : overrides) ov[o.key] = o.value;
  j["overrides"] = ov;
  j["configuration"] = base.two_spheres() ? "sphere-sphere" : (base.wall ? "sphere-wall" : "free sphere");
  j["vary"] = opt.vary;
  j["column"] = q.column;
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
  const auto ran = std::find_if(pts.begin(), pts.end(), [](const PointResult& p) { return p.ok; });
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

int sweep(const std::string& scene_path, const std::vector<Override>& overrides, const SweepOptions& opt) {
  const Quantity* q = quantity(opt.vary);
  if (!q) throw InputError("--vary", opt.vary, "unknown quantity (expected velocity, viscosity, diameter, density)");
  check_options(opt);

  const Scene base = load_scene(scene_path, overrides);
  const std::vector<double> values = sweep_values(opt);
  const auto t_scenes = WallClock::now();
  const std::vector<Scene> scenes = sweep_scenes(scene_path, overrides, base, opt.vary, values);
  const double scenes_check_s = seconds_since(t_scenes);
  std::vector<PointResult> pts(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) pts[i].value = values[i];
  const int jobs = study::job_count(opt.jobs, pts.size());
  // The folder is one unit (apps/output_unit.hpp): the sweep is built beside it and swapped in when complete.
  // sweep.partial marks sweep.csv as incomplete until then; a sweep stopped by a write error keeps both beside the folder.
  // Under mpirun, rank 0 alone takes the folder, writes and prints; a refused folder ends every rank.
  if (const int differ = cluster::agree(sweep_inputs(scenes, opt))) return differ;  // ranks on other inputs: refused
  std::optional<OutputUnit> unit;
  const int refused = cluster::on_rank0([&] {
    unit.emplace(opt.out, fs::path("out") / (base.name + "-sweep_" + opt.vary), base.path);
    write_file_atomic(unit->dir() / "sweep.partial",
                      "sweep in progress or interrupted (pid " + std::to_string(::getpid()) +
                          "): sweep.csv holds only the points finished so far; a complete sweep removes this file and writes sweep.json\n");
  });
  if (refused) return refused;
  // Under mpirun, ranks > 0 run points for rank 0 (docs/cluster.md).
  if (cluster::world().rank > 0) {
    cluster::run_distributed(pts.size(), jobs, [&](std::size_t i) { return encode_point(point_result(scenes[i], i, values[i])); }, {});
    return 0;
  }
  const fs::path& dir = unit->dir();
  const Tally tally = run_points(scenes, pts, opt, *q, dir, jobs);
  if (!tally.write_error.empty()) stop_on_write_error(*unit, tally, opt);
  const int failed = tally.failed;

  // Table, failures, throughput; sweep.json.
  Outcome outcome = report_points(pts, opt, *q, base, jobs, tally);
  outcome.scenes_check_s = scenes_check_s;
  nlohmann::ordered_json j = sweep_json(scene_path, overrides, base, opt, *q, pts, outcome);
  j["run"] = unit->run();
  write_file_atomic(dir / "sweep.json", j.dump(2) + "\n");
  fs::remove(dir / "sweep.partial");
  std::string dem_line;
  if (opt.export_format == "dem") {
    const std::optional<double> e_dry = j.contains("e_dry") ? std::optional<double>(j["e_dry"].get<double>()) : std::nullopt;
    dem_line = export_dem(dir, base, {scene_path, opt.vary, q->column, e_dry}, dem_points(pts));
  }
  if (opt.plot) run_plot_script("plot_sweep.py", *unit, "sweep.png");
  unit->commit();
  if (!dem_line.empty()) std::cout << dem_line << "\n";
  std::cout << "wrote " << (unit->target() / "sweep.csv").string() << " and " << (unit->target() / "sweep.json").string()
            << (dem_line.empty() ? "" : ", dem.csv, dem_table.csv, dem.json") << "\n";
  if (failed) {  // stdout may go to a file or a pipe: the failure is also said where errors go
    std::cout.flush();
    std::cerr << "imcol: error: " << failed << " of " << opt.points << " sweep points failed; their reasons are in "
              << (unit->target() / "sweep.json").string() << " (failures) and " << (unit->target() / "sweep.csv").string() << " (status, message)\n";
  }
  return failed ? 3 : 0;
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

void put_sweep_settings(nlohmann::ordered_json& j, const SweepOptions& opt, const char* column) {
  j["vary"] = opt.vary;
  j["column"] = column;
  j["from"] = opt.from;
  j["to"] = opt.to;
  j["points"] = opt.points;
  j["spacing"] = opt.spacing;
}

}  // namespace imcol
