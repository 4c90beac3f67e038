// SPDX-License-Identifier: BSD-3-Clause
#include "apps/calibrate.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <tuple>
#include <variant>

#include "apps/calibrate_files.hpp"
#include "apps/calibrate_progress.hpp"
#include "apps/calibrate_runner.hpp"
#include "apps/rank_inputs.hpp"
#include "apps/cluster.hpp"
#include "apps/format.hpp"
#include "apps/output_unit.hpp"
#include "study/parallel_runs.hpp"
#include "apps/plot.hpp"
#include "apps/scene_value.hpp"
#include "calibrate/evaluation_cache.hpp"
#include "core/errors.hpp"
#include "core/text_file.hpp"
#include "core/timing.hpp"
#include "core/toml_reader.hpp"

namespace imcol {

namespace fs = std::filesystem;
using calib::FitParameter;
using calib::MeasuredTable;
using calib::MeasuredTrajectory;
using calib::Measurement;
using calib::TrajectoryWindow;

namespace {

std::optional<double> parse_number(const std::string& s) {
  const char* c = s.c_str();
  char* end = nullptr;
  const double v = std::strtod(c, &end);
  if (s.empty() || end == c || *end != '\0' || std::isspace(static_cast<unsigned char>(s[0])) || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// --window A:B: seconds before (A < 0) and after (B > 0) the measured contact.
std::pair<double, double> parse_window(const std::string& text) {
  auto bad = [&](const std::string& why) { throw InputError("command line", "--window", why + " (got '" + text + "')"); };
  const auto colon = text.find(':');
  if (colon == std::string::npos) bad("expected A:B, seconds before and after the measured contact (e.g. -0.01:0.02)");
  const auto a = parse_number(text.substr(0, colon)), b = parse_number(text.substr(colon + 1));
  if (!a || !b) bad("A and B must be finite numbers (seconds), as in -0.01:0.02");
  if (!(*a < 0)) bad("A must be negative: the window starts before the measured contact");
  if (!(*b > 0)) bad("B must be positive: the window ends after the measured contact");
  return {*a, *b};
}

const char* kind_of(const Measurement& m) { return std::holds_alternative<MeasuredTrajectory>(m) ? "a trajectory" : "an e table"; }

std::vector<Override> with_values(const std::vector<Override>& overrides, const std::vector<FitParameter>& params,
                                  const std::vector<double>& values) {
  std::vector<Override> ov = overrides;
  for (auto& o : calib::overrides_for(params, values)) ov.push_back(std::move(o));
  return ov;
}

/// A table's rows: no fitted key among its columns (a row's value would replace the fitted one), and every row's
/// scene valid (calib::check_table_keys: InputError naming the row's line).
void check_table(const MeasuredTable& t, const std::string& scene_path, const std::vector<Override>& overrides,
                 const std::vector<FitParameter>& params) {
  for (const auto& p : params)
    if (std::find(t.keys.begin(), t.keys.end(), p.key) != t.keys.end())
      throw InputError("command line", "--fit", p.key + " is a column of " + t.path + ": each row sets it, so it cannot be fitted");
  calib::check_table_keys(t, scene_path, overrides);
}

/// The search starts at the scene's own values, clamped into the bounds; a key the scene leaves to a default it does
/// not hold starts at the middle of its range (the geometric middle on a log scale).
std::vector<StartValue> start_values(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                                     const std::vector<FitParameter>& params) {
  std::vector<StartValue> out;
  for (const auto& p : params) {
    StartValue s;
    if (const auto v = scene_value(scene_path, overrides, base, p.key)) {
      s.scene = *v;
      s.value = std::clamp(*v, p.lo, p.hi);
      s.from = *v == s.value ? "scene" : "scene, clamped to the bounds";
    } else {
      s.value = calib::value_of(p, 0.5);
      s.from = "middle of the bounds (the scene does not set the key)";
    }
    out.push_back(s);
  }
  return out;
}

/// The residuals the objective averages: the window's samples times the measured columns, or the table's rows.
std::size_t residual_count(const Measurement& m, const std::optional<TrajectoryWindow>& w) {
  if (const auto* t = std::get_if<MeasuredTrajectory>(&m)) {
    const auto [k0, k1] = calib::window_rows(*t, *w);
    return (k1 - k0) * t->columns.size();
  }
  return std::get<MeasuredTable>(m).e.size();
}

/// Every input, read and checked on every rank before anything runs.
struct Inputs {
  Scene base;
  std::vector<FitParameter> params;
  std::vector<StartValue> start;
  std::string data_text;  // the measurement file's text, as read once
  Measurement data;
  std::optional<TrajectoryWindow> window;
  std::optional<Measurement> held_out;  // --validate
  std::optional<TrajectoryWindow> held_window;
  calib::CacheContext cache_context;     // --cache: what its evaluations depend on,
  std::string cache_text;                // the file's content on this process ("" when new),
  calib::EvaluationCache cache;          // and its evaluations
};

/// The cache file's content; "" when it is not there yet. A regular file of at most calib::kMaxCacheBytes.
std::string cache_file_text(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec))) return "";
  return read_text_file(path, "cache", calib::kMaxCacheBytes, "", "--cache");
}

/// The cache file can be appended to (or made): checked on every rank before anything runs, as rank 0 appends later.
void check_cache_writable(const std::string& path) {
  std::error_code ec;
  const fs::path p(path);
  const fs::path folder = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::exists(p, ec) && !fs::is_directory(folder, ec))
    throw InputError("command line", "--cache", "the folder of '" + path + "' does not exist");
  if (::access(fs::exists(p, ec) ? path.c_str() : folder.c_str(), W_OK) != 0)
    throw InputError("command line", "--cache", "'" + path + "' cannot be written: " + std::strerror(errno));
}

/// What the evaluations of a calibration with these inputs depend on.
calib::CacheContext cache_context(const Inputs& in, const std::vector<Override>& overrides) {
  calib::CacheContext c;
  c.imcol_version = IMCOL_VERSION;
  c.scene_text = read_scene_file(in.base.path);
  c.measurement_text = in.data_text;
  for (const auto& o : overrides) c.overrides.push_back(o.key + "=" + o.value);
  for (const auto& p : in.params) c.fit_keys.push_back(p.key);
  if (in.window) c.window = {in.window->t_contact, in.window->before, in.window->after, in.window->tau_max};
  return c;
}

Inputs read_inputs(const std::string& scene_path, const std::vector<Override>& overrides, const CalibrateOptions& opt) {
  Inputs in;
  in.base = load_scene(scene_path, overrides);
  if (opt.fits.empty()) throw InputError("command line", "--fit", "give at least one parameter: --fit KEY=LO:HI[:log]");
  for (const auto& f : opt.fits) {
    FitParameter p = calib::parse_fit_parameter(f, scene_path, overrides);
    for (const auto& q : in.params)
      if (q.key == p.key) throw InputError("command line", "--fit", p.key + " is given twice");
    in.params.push_back(p);
  }
  const auto& so = opt.search;
  if (so.profile_points == 1) throw InputError("command line", "--profile-points", "must be 0 (no profiles) or at least 2 (got 1)");
  in.data_text = read_text_file(opt.data, "measurement", calib::kMaxMeasurementBytes, "CSV");
  in.data = calib::parse_measurement(opt.data, in.data_text);
  const bool trajectory = std::holds_alternative<MeasuredTrajectory>(in.data);
  std::optional<double> before, after;
  if (!trajectory && (!opt.window.empty() || opt.offset_max))
    throw InputError("command line", opt.window.empty() ? "--offset-max" : "--window",
                     "applies to a trajectory; " + opt.data + " is an e table");
  if (!opt.window.empty()) std::tie(before, after) = parse_window(opt.window);
  if (trajectory) in.window = calib::trajectory_window(std::get<MeasuredTrajectory>(in.data), in.base, before, after, opt.offset_max);
  else check_table(std::get<MeasuredTable>(in.data), scene_path, overrides, in.params);
  if (!opt.validate.empty()) {
    in.held_out = calib::read_measurement(opt.validate);
    if (in.held_out->index() != in.data.index())
      throw InputError("command line", "--validate",
                       opt.validate + " is " + kind_of(*in.held_out) + " but " + opt.data + " (--data) is " + kind_of(in.data) +
                           ": the validation is a measurement of the same kind");
    if (trajectory)
      in.held_window = calib::trajectory_window(std::get<MeasuredTrajectory>(*in.held_out), in.base, before, after, opt.offset_max);
    else
      check_table(std::get<MeasuredTable>(*in.held_out), scene_path, overrides, in.params);
  }
  // The default interval estimates the noise from the best fit's residuals: more of them than fitted parameters.
  const std::size_t n = residual_count(in.data, in.window), p = in.params.size() + (trajectory ? 1 : 0);
  if (so.profile_points > 0 && !so.factor && n <= p)
    throw InputError(opt.data, "",
                     std::to_string(n) + " residuals" + (trajectory ? " in the window" : "") + " for " + std::to_string(p) +
                         " fitted parameters" + (trajectory ? " (the time offset among them)" : "") +
                         ": too few to fit them and estimate the noise for the confidence interval; give more data, or "
                         "--factor F to set the interval's factor directly");
  in.start = start_values(scene_path, overrides, in.base, in.params);
  if (!opt.cache.empty()) {
    in.cache_context = cache_context(in, overrides);
    in.cache_text = cache_file_text(opt.cache);
    check_cache_writable(opt.cache);
    in.cache = calib::EvaluationCache(opt.cache, in.cache_text, in.cache_context);
  }
  return in;
}

/// Scores one set of values on the measurement; never throws (a failure is an evaluation that is not ok).
calib::Evaluation score(const Inputs& in, const Measurement& m, const std::optional<TrajectoryWindow>& w, const std::string& scene_path,
                        const std::vector<Override>& overrides, const std::vector<double>& values) {
  try {
    const auto ov = with_values(overrides, in.params, values);
    if (const auto* t = std::get_if<MeasuredTrajectory>(&m)) return calib::evaluate_trajectory(*t, *w, scene_path, ov);
    return calib::evaluate_table(std::get<MeasuredTable>(m), scene_path, ov);
  } catch (const std::exception& e) {
    calib::Evaluation ev;
    ev.objective = ev.rms = INFINITY;
    ev.message = e.what();
    return ev;
  }
}

/// "0.024123"; the interval "[0.0221, 0.0262]", an end that reaches the bound written as "open at the bound".
std::string value_text(double v) {
  std::ostringstream os;
  os << std::setprecision(6) << v;
  return os.str();
}

std::string interval_text(const calib::Profile& p, const FitParameter& f, const calib::FactorRule& rule) {
  auto end = [&](const std::optional<double>& v, double bound) {
    return v ? value_text(*v) : "open at " + std::string(bound == f.lo ? "lo " : "hi ") + value_text(bound);
  };
  std::string why = rule.given ? "objective within " + value_text(rule.factor) + " x the best"
                               : value_text(100 * rule.confidence) + " % confidence: objective within " + value_text(rule.factor) +
                                     " x the best";
  return "[" + end(p.lo, f.lo) + ", " + end(p.hi, f.hi) + "] (" + why + ")";
}

/// The per-stage table (evaluations, failures, best rms, wall time) and the totals line.
void print_stages(const calib::SearchResult& res, const StageTimes& times, double wall, int jobs, int ranks) {
  std::cout << std::left << std::setw(10) << "stage" << std::right << std::setw(12) << "evaluations" << std::setw(8) << "failed"
            << std::setw(14) << "best rms" << std::setw(10) << "wall s" << "\n";
  for (const auto stage : {calib::Stage::start, calib::Stage::scan, calib::Stage::local, calib::Stage::profile, calib::Stage::edge}) {
    int n = 0, failed = 0;
    double best = INFINITY;
    for (const auto& e : res.evaluations)
      if (e.stage == stage) {
        ++n;
        if (!e.eval.ok) ++failed;
        else best = std::min(best, e.eval.rms);
      }
    if (!n) continue;
    const double t = times.wall(stage);
    std::cout << std::left << std::setw(10) << calib::stage_name(stage) << std::right << std::setw(12) << n << std::setw(8) << failed
              << std::setw(14) << sci(best, 3) << std::setw(10) << (std::isfinite(t) ? fixed(t, 2) : "-") << "\n";
  }
  std::cout << res.evaluations.size() << " evaluations (" << res.failed << " failed) in " << fixed(wall, 2) << " s on " << jobs
            << (jobs == 1 ? " thread" : " threads") << (ranks > 1 ? " on each of " + std::to_string(ranks) + " ranks" : std::string()) << "\n";
}

/// The best values with their intervals, and notes on intervals open at both bounds or not resolved.
void print_best(const Inputs& in, const CalibrateOptions& opt, const calib::SearchResult& res, bool trajectory) {
  std::cout << "best: rms " << sci(res.best_eval.rms, 3) << (trajectory ? " m" : "") << " (objective " << sci(res.best_eval.objective, 3)
            << (trajectory ? " m^2" : "") << ")";
  if (res.best_eval.tau) std::cout << ", time offset tau = " << fixed(1e3 * *res.best_eval.tau, 3) << " ms (measurement clock minus simulation)";
  std::cout << "\n";
  for (std::size_t k = 0; k < in.params.size(); ++k) {
    std::cout << in.params[k].key << " = " << value_text(res.best[k]);
    if (k < res.profiles.size()) std::cout << "  " << interval_text(res.profiles[k], in.params[k], res.rule);
    std::cout << "\n";
  }
  for (std::size_t k = 0; k < res.profiles.size() && k < in.params.size(); ++k)
    if (!res.profiles[k].lo && !res.profiles[k].hi)
      std::cout << "note: the objective stays within " << value_text(res.rule.factor) << " x the best across the whole range of "
                << in.params[k].key << ": the measurement does not determine it"
                << (res.rule.given ? " within this factor" : " at this confidence") << "\n";
  for (std::size_t k = 0; k < res.profiles.size() && k < in.params.size(); ++k)
    if (!res.profiles[k].resolved)
      std::cout << "note: after " << opt.search.refine << " rounds (--refine) an end of the interval of " << in.params[k].key
                << " still lies in a bracket wider than " << value_text(opt.search.refine_to)
                << " of the interval (--refine-to): raise --refine for sharper ends\n";
}

/// The hold-out's rms under the fitted values; a table's rows, measured against simulated.
void print_validation(const Inputs& in, const CalibrateOptions& opt, const Validation& val, bool trajectory) {
  std::cout << "validation on " << opt.validate << " (not used in the fit";
  if (trajectory) std::cout << "; the time offset refitted";
  std::cout << "): ";
  if (!val.eval.ok) {
    std::cout << "failed: " << val.eval.message << "\n";
    return;
  }
  std::cout << "rms " << sci(val.eval.rms, 3) << (trajectory ? " m" : "");
  if (val.eval.tau) std::cout << ", tau = " << fixed(1e3 * *val.eval.tau, 3) << " ms";
  std::cout << "\n";
  if (const auto* t = std::get_if<MeasuredTable>(&*in.held_out))
    for (std::size_t r = 0; r < t->e.size(); ++r) {
      std::cout << "  " << t->path << ":" << t->lines[r] << ":";
      for (std::size_t k = 0; k < t->keys.size(); ++k) std::cout << " " << t->keys[k] << " = " << value_text(t->values[r][k]);
      const double sim = r < val.eval.e_sim.size() ? val.eval.e_sim[r] : NAN;
      std::cout << ": e_meas " << fixed(t->e[r], 4) << ", e_sim " << (std::isfinite(sim) ? fixed(sim, 4) : "-") << "\n";
    }
}

/// The closing lines on stdout: the stages, the best values with their intervals, the validation.
void print_result(const Inputs& in, const CalibrateOptions& opt, const calib::SearchResult& res, const StageTimes& times,
                  const Validation* val, double wall, int jobs, int ranks) {
  const bool trajectory = std::holds_alternative<MeasuredTrajectory>(in.data);
  print_stages(res, times, wall, jobs, ranks);
  if (!res.best_eval.ok) return;
  print_best(in, opt, res, trajectory);
  if (val) print_validation(in, opt, *val, trajectory);
}

/// Rank 0's output folder, taken before anything runs; non-zero when refused (another run writing it, a folder
/// imcol did not write), which ends every rank.
int take_output_unit(std::optional<OutputUnit>& unit, const Inputs& in, const CalibrateOptions& opt) {
  return cluster::on_rank0([&] {
    unit.emplace(opt.out, fs::path("out") / (in.base.name + "-calibrate"), in.base.path,
                 std::vector<RunInput>{{"--data", opt.data}, {"--validate", opt.validate}, {"--cache", opt.cache}});
  });
}

/// The cache as rank 0 read it made every rank's, and rank 0's writer (rank 0 alone appends to it, from here on);
/// non-zero when refused.
int open_cache(Inputs& in, const CalibrateOptions& opt, int rank, std::optional<calib::CacheWriter>& writer) {
  if (opt.cache.empty()) return 0;
  std::string text = in.cache_text;
  cluster::share(text);
  if (rank > 0) in.cache = calib::EvaluationCache(opt.cache, text, in.cache_context);
  return cluster::on_rank0([&] { writer.emplace(opt.cache, in.cache, in.cache_context); });
}

/// The runner over the cluster; with a cache, each finished work item appended to it before the search uses it.
calib::Runner search_runner(const CalibrateOptions& opt, std::optional<calib::CacheWriter>& cache_writer) {
  calib::Runner runner = cluster_runner(opt.jobs);
  if (cache_writer) runner.run = [run = runner.run, &cache_writer](std::size_t n, const std::function<std::string(std::size_t)>& work,
                                                                  const std::function<void(std::size_t, std::string, int)>& done) {
    run(n, work, [&](std::size_t i, std::string bytes, int rank) {
      cache_writer->add_item(bytes);  // before the search uses it: a kill after this loses nothing
      done(i, std::move(bytes), rank);
    });
  };
  return runner;
}

/// The search on every rank from the start values, evaluations found in the cache taken from it.
calib::SearchResult run_search(const Inputs& in, const std::string& scene_path, const std::vector<Override>& overrides,
                               const CalibrateOptions& opt, ProgressLine& progress, std::optional<calib::CacheWriter>& cache_writer,
                               int rank) {
  std::vector<double> start;
  for (const auto& s : in.start) start.push_back(s.value);
  auto evaluate = [&](const std::vector<double>& values) {
    if (auto held = in.cache.find(values)) return *held;
    calib::Evaluation e = score(in, in.data, in.window, scene_path, overrides, values);
    progress.add_evaluation(e.wall_s);
    return e;
  };
  cluster::Hold hold;  // the ranks wait on each other from stage to stage
  calib::SearchOptions so = opt.search;
  so.inner_parameters = std::holds_alternative<MeasuredTrajectory>(in.data) ? 1 : 0;  // the time offset tau, fitted in every evaluation
  return calib::search(in.params, start, evaluate, so, search_runner(opt, cache_writer), rank == 0 ? progress.callback() : calib::Progress{});
}

/// A trajectory's fitted run, for best.csv and its summary's blocks; none for a table, without a best or when it
/// fails (`error` says why).
std::optional<RunResult> fitted_run(const Inputs& in, const std::string& scene_path, const std::vector<Override>& overrides,
                                    const calib::SearchResult& res, std::string& error) {
  std::optional<RunResult> run;
  if (!res.best_eval.ok || !std::holds_alternative<MeasuredTrajectory>(in.data)) return run;
  try {
    run = simulate(calib::trajectory_scene(*in.window, scene_path, with_values(overrides, in.params, res.best)), false,
                   Recording::kinematics);
    // The same run the search scored: the same objective (best.csv shows what was fitted).
    const double again = calib::trajectory_objective(std::get<MeasuredTrajectory>(in.data), *in.window, *run).objective;
    if (!(std::abs(again - res.best_eval.objective) <= 1e-9 * res.best_eval.objective))
      std::cerr << "imcol: warning: the fitted run scored again gives objective " << again << " against the search's "
                << res.best_eval.objective << "; best.csv holds the run made again\n";
  } catch (const std::exception& e) {
    error = e.what();
  }
  return run;
}

/// The hold-out scored under the fitted values; none without a hold-out or a best.
std::optional<Validation> held_out_validation(const Inputs& in, const std::string& scene_path, const std::vector<Override>& overrides,
                                              const calib::SearchResult& res) {
  if (!in.held_out || !res.best_eval.ok) return std::nullopt;
  Validation val;
  val.eval = score(in, *in.held_out, in.held_window, scene_path, overrides, res.best);
  return val;
}

void print_heading(const Inputs& in, const CalibrateOptions& opt) {
  std::cout << "scene " << in.base.name << ": calibrating";
  for (const auto& p : in.params) std::cout << " " << p.key;
  std::cout << " against " << opt.data << " (" << kind_of(in.data) << ")\n";
}

/// The record the files are written from (its validation and fitted run point into the caller's).
CalibrationRecord calibration_record(const Inputs& in, const std::string& scene_path, const std::vector<Override>& overrides,
                                     const CalibrateOptions& opt, const calib::SearchResult& res) {
  CalibrationRecord rec;
  rec.scene_path = scene_path;
  rec.overrides = overrides;
  rec.base = in.base;
  rec.params = in.params;
  rec.start = in.start;
  rec.data = in.data;
  rec.data_text = in.data_text;
  rec.window = in.window;
  rec.held_out = in.held_out;
  rec.held_window = in.held_window;
  rec.search = opt.search;
  rec.search.inner_parameters = std::holds_alternative<MeasuredTrajectory>(in.data) ? 1 : 0;
  rec.result = res;
  return rec;
}

/// The cache's use (held, reused, added) into the record, and its line on stdout.
void add_cache_use(CalibrationRecord& rec, const Inputs& in, const CalibrateOptions& opt, const calib::CacheWriter& writer) {
  const calib::SearchResult& res = rec.result;
  rec.cache.emplace();
  rec.cache->path = opt.cache;
  rec.cache->held = in.cache.size();
  for (const auto& e : res.evaluations) rec.cache->reused += in.cache.contains(e.values) ? 1 : 0;
  rec.cache->added = writer.added();
  std::cout << "cache " << opt.cache << ": " << rec.cache->reused << " of " << res.evaluations.size()
            << " evaluations taken from it, " << rec.cache->added << " added\n";
}

/// Writes the files (and the plot) into the unit and commits it; 3 when no evaluation succeeded.
int write_output(OutputUnit& unit, const CalibrateOptions& opt, const CalibrationRecord& rec) {
  write_calibration_files(unit.dir(), rec, unit.run());
  if (opt.plot) {
    std::cout.flush();
    run_plot_script("plot_calibration.py", unit, "calibration.png");
  }
  unit.commit();
  const fs::path& target = unit.target();
  std::cout << "wrote " << (target / "calibration.json").string() << ", calibration.csv, measured.csv and best.csv\n";
  if (!rec.result.best_eval.ok) {
    std::cout.flush();
    std::cerr << "imcol: error: no evaluation succeeded; their reasons are in " << (target / "calibration.csv").string() << " (status, message)\n";
    return 3;
  }
  return 0;
}

}  // namespace

int calibrate(const std::string& scene_path, const std::vector<Override>& overrides, const CalibrateOptions& opt) {
  Inputs in = read_inputs(scene_path, overrides, opt);
  // MPI starts here, every rank having checked the same inputs. Rank 0 alone writes.
  const cluster::World world = cluster::world();
  if (const int differ = cluster::agree(calibrate_inputs(in.base, in.data, in.held_out, opt))) return differ;  // ranks on other inputs: refused
  std::optional<OutputUnit> unit;
  if (const int refused = take_output_unit(unit, in, opt)) return refused;
  std::optional<calib::CacheWriter> cache_writer;
  if (const int refused = open_cache(in, opt, world.rank, cache_writer)) return refused;

  const int jobs = study::job_count(opt.jobs, 1u << 20);  // threads a rank (each stage uses at most one per work item)
  const bool trajectory = std::holds_alternative<MeasuredTrajectory>(in.data);
  ProgressLine progress(world.rank == 0 && opt.progress && isatty(STDERR_FILENO), in.params.size(), opt.search,
                        jobs * world.size, trajectory ? "m" : "");
  const auto t0 = WallClock::now();
  calib::SearchResult res = run_search(in, scene_path, overrides, opt, progress, cache_writer, world.rank);
  const double wall = seconds_since(t0);
  progress.finish();
  if (world.rank > 0) return 0;

  sort_evaluations(res);
  std::string best_run_error;
  const std::optional<RunResult> best_run = fitted_run(in, scene_path, overrides, res, best_run_error);
  const std::optional<Validation> val = held_out_validation(in, scene_path, overrides, res);
  print_heading(in, opt);
  print_result(in, opt, res, progress.stage_times(), val ? &*val : nullptr, wall, jobs, world.size);

  CalibrationRecord rec = calibration_record(in, scene_path, overrides, opt, res);
  rec.validation = val ? &*val : nullptr;
  rec.best_run = best_run ? &*best_run : nullptr;
  rec.best_run_error = best_run_error;
  rec.wall_s = wall;
  rec.jobs = jobs;
  rec.ranks = world.size;
  rec.stage_times = progress.stage_times();
  if (cache_writer) add_cache_use(rec, in, opt, *cache_writer);
  return write_output(*unit, opt, rec);
}

}  // namespace imcol
