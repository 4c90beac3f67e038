// SPDX-License-Identifier: BSD-3-Clause
#include "apps/calibrate.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <variant>

#include "apps/calibrate_files.hpp"
#include "apps/calibrate_progress.hpp"
#include "apps/cluster.hpp"
#include "apps/format.hpp"
#include "apps/output_unit.hpp"
#include "apps/plot.hpp"
#include "apps/rank_inputs.hpp"
#include "calibrate/evaluation_cache.hpp"
#include "core/errors.hpp"
#include "core/text_file.hpp"
#include "core/toml_reader.hpp"
#include "study/parallel_runs.hpp"

namespace imcol {

namespace fs = std::filesystem;
using calib::FitParameter;
using calib::MeasuredTable;
using calib::MeasuredTrajectory;
using study::CalibrationInputs;
using study::CalibrationResult;

namespace {

/// The evaluation cache (--cache): what its evaluations depend on, the file's content on this process ("" when
/// new), and its evaluations.
struct Cache {
  calib::CacheContext context;
  std::string text;
  calib::EvaluationCache held;
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
calib::CacheContext cache_context(const CalibrationInputs& in) {
  calib::CacheContext c;
  c.imcol_version = IMCOL_VERSION;
  c.scene_text = read_scene_file(in.base.path);
  c.measurement_text = in.data_text;
  for (const auto& o : in.overrides) c.overrides.push_back(o.key + "=" + o.value);
  for (const auto& p : in.params) c.fit_keys.push_back(p.key);
  if (in.window) c.window = {in.window->t_contact, in.window->before, in.window->after, in.window->tau_max};
  return c;
}

/// The cache as this process reads it, checked before anything runs; none without --cache.
std::optional<Cache> read_cache(const CalibrationInputs& in, const CalibrateOptions& opt) {
  if (opt.cache.empty()) return std::nullopt;
  Cache c;
  c.context = cache_context(in);
  c.text = cache_file_text(opt.cache);
  check_cache_writable(opt.cache);
  c.held = calib::EvaluationCache(opt.cache, c.text, c.context);
  return c;
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
void print_stages(const CalibrationResult& r) {
  const calib::SearchResult& res = r.search;
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
    const double t = r.stage_times.wall(stage);
    std::cout << std::left << std::setw(10) << calib::stage_name(stage) << std::right << std::setw(12) << n << std::setw(8) << failed
              << std::setw(14) << sci(best, 3) << std::setw(10) << (std::isfinite(t) ? fixed(t, 2) : "-") << "\n";
  }
  std::cout << res.evaluations.size() << " evaluations (" << res.failed << " failed) in " << fixed(r.wall_s, 2) << " s on " << r.jobs
            << (r.jobs == 1 ? " thread" : " threads") << (r.ranks > 1 ? " on each of " + std::to_string(r.ranks) + " ranks" : std::string())
            << "\n";
}

/// The best values with their intervals, and notes on intervals open at both bounds or not resolved.
void print_best(const CalibrationInputs& in, const calib::SearchResult& res) {
  const bool trajectory = in.trajectory();
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
      std::cout << "note: after " << in.search.refine << " rounds (--refine) an end of the interval of " << in.params[k].key
                << " still lies in a bracket wider than " << value_text(in.search.refine_to)
                << " of the interval (--refine-to): raise --refine for sharper ends\n";
}

/// The hold-out's rms under the fitted values; a table's rows, measured against simulated.
void print_validation(const CalibrationInputs& in, const calib::Evaluation& val) {
  const bool trajectory = in.trajectory();
  std::cout << "validation on " << in.held_out_path << " (not used in the fit";
  if (trajectory) std::cout << "; the time offset refitted";
  std::cout << "): ";
  if (!val.ok) {
    std::cout << "failed: " << val.message << "\n";
    return;
  }
  std::cout << "rms " << sci(val.rms, 3) << (trajectory ? " m" : "");
  if (val.tau) std::cout << ", tau = " << fixed(1e3 * *val.tau, 3) << " ms";
  std::cout << "\n";
  if (const auto* t = std::get_if<MeasuredTable>(&*in.held_out))
    for (std::size_t r = 0; r < t->e.size(); ++r) {
      std::cout << "  " << t->path << ":" << t->lines[r] << ":";
      for (std::size_t k = 0; k < t->keys.size(); ++k) std::cout << " " << t->keys[k] << " = " << value_text(t->values[r][k]);
      const double sim = r < val.e_sim.size() ? val.e_sim[r] : NAN;
      std::cout << ": e_meas " << fixed(t->e[r], 4) << ", e_sim " << (std::isfinite(sim) ? fixed(sim, 4) : "-") << "\n";
    }
}

/// The lines on stdout: the heading, the stages, the best values with their intervals, the validation.
void print_result(const CalibrationInputs& in, const CalibrationResult& r) {
  std::cout << "scene " << in.base.name << ": calibrating";
  for (const auto& p : in.params) std::cout << " " << p.key;
  std::cout << " against " << in.data_path << " (" << study::kind_of(in.data) << ")\n";
  print_stages(r);
  if (!r.search.best_eval.ok) return;
  print_best(in, r.search);
  if (r.validation) print_validation(in, *r.validation);
}

/// Rank 0's output folder, taken before anything runs; non-zero when refused (another run writing it, a folder
/// imcol did not write), which ends every rank.
int take_output_unit(std::optional<OutputUnit>& unit, const CalibrationInputs& in, const CalibrateOptions& opt) {
  return cluster::on_rank0([&] {
    unit.emplace(opt.out, fs::path("out") / (in.base.name + "-calibrate"), in.base.path,
                 std::vector<RunInput>{{"--data", opt.data}, {"--validate", opt.validate}, {"--cache", opt.cache}});
  });
}

/// The cache as rank 0 read it made every rank's, and rank 0's writer (rank 0 alone appends to it, from here on);
/// non-zero when refused.
int open_cache(std::optional<Cache>& cache, const CalibrateOptions& opt, int rank, std::optional<calib::CacheWriter>& writer) {
  if (!cache) return 0;
  std::string text = cache->text;
  cluster::share(text);
  if (rank > 0) cache->held = calib::EvaluationCache(opt.cache, text, cache->context);
  return cluster::on_rank0([&] { writer.emplace(opt.cache, cache->held, cache->context); });
}

/// The cache as the calibration's store: its evaluations found, each finished work item appended by rank 0.
study::EvaluationStore cache_store(const std::optional<Cache>& cache, std::optional<calib::CacheWriter>& writer) {
  study::EvaluationStore store;
  if (!cache) return store;
  store.find = [&held = cache->held](const std::vector<double>& values) { return held.find(values); };
  if (writer) store.keep = [&writer](const std::string& bytes) { writer->add_item(bytes); };
  return store;
}

/// The cache's use (held, reused, added), and its line on stdout.
CacheUse cache_use(const Cache& cache, const CalibrateOptions& opt, const calib::CacheWriter& writer, const calib::SearchResult& res) {
  CacheUse use;
  use.path = opt.cache;
  use.held = cache.held.size();
  for (const auto& e : res.evaluations) use.reused += cache.held.contains(e.values) ? 1 : 0;
  use.added = writer.added();
  std::cout << "cache " << opt.cache << ": " << use.reused << " of " << res.evaluations.size() << " evaluations taken from it, "
            << use.added << " added\n";
  return use;
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
  if (!rec.result.search.best_eval.ok) {
    std::cout.flush();
    std::cerr << "imcol: error: no evaluation succeeded; their reasons are in " << (target / "calibration.csv").string() << " (status, message)\n";
    return 3;
  }
  return 0;
}

/// The calibration on every rank, its progress line on rank 0's terminal.
CalibrationResult run_on_cluster(const CalibrationInputs& in, const CalibrateOptions& opt, const study::EvaluationStore& store) {
  const cluster::World world = cluster::world();
  const int jobs = study::job_count(opt.jobs, 1u << 20);
  ProgressLine progress(world.rank == 0 && opt.progress && isatty(STDERR_FILENO), in.params.size(), in.search, jobs * world.size,
                        in.trajectory() ? "m" : "");
  study::CalibrationWatch watch;
  watch.items = progress.callback();
  watch.evaluated = [&progress](double wall_s) { progress.add_evaluation(wall_s); };
  cluster::Hold hold;  // the ranks wait on each other from stage to stage
  CalibrationResult r = study::run_calibration(in, cluster_executor(opt.jobs), {}, watch, store);
  progress.finish();
  return r;
}

}  // namespace

int calibrate(const std::string& scene_path, const std::vector<Override>& overrides, const CalibrateOptions& opt) {
  const CalibrationInputs in = study::read_calibration_inputs(scene_path, overrides, opt);
  std::optional<Cache> cache = read_cache(in, opt);
  // MPI starts here, every rank having checked the same inputs. Rank 0 alone writes.
  const cluster::World world = cluster::world();
  if (const int differ = cluster::agree(calibrate_inputs(in.base, in.data, in.held_out, opt))) return differ;  // ranks on other inputs: refused
  std::optional<OutputUnit> unit;
  if (const int refused = take_output_unit(unit, in, opt)) return refused;
  std::optional<calib::CacheWriter> cache_writer;
  if (const int refused = open_cache(cache, opt, world.rank, cache_writer)) return refused;

  const CalibrationResult r = run_on_cluster(in, opt, cache_store(cache, cache_writer));
  if (world.rank > 0) return 0;
  if (!r.best_run_warning.empty()) std::cerr << "imcol: warning: " << r.best_run_warning << "\n";
  print_result(in, r);
  CalibrationRecord rec{in, r, std::nullopt};
  if (cache_writer) rec.cache = cache_use(*cache, opt, *cache_writer, r.search);
  return write_output(*unit, opt, rec);
}

}  // namespace imcol
