// SPDX-License-Identifier: BSD-3-Clause
// The calibration on an Executor: the search's work items handed out as a calib::Runner, its evaluations scored
// from the inputs (or found in the store), then the fitted run and the held-out measurement on the deciding process.
#include "study/calibrate.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <mutex>
#include <sstream>
#include <utility>
#include <variant>

#include "calibrate/fit_parameter.hpp"
#include "core/timing.hpp"
#include "core/work_scope.hpp"
#include "study/parallel_runs.hpp"

namespace imcol::study {

using calib::MeasuredTable;
using calib::MeasuredTrajectory;

namespace {

std::vector<Override> with_values(const CalibrationInputs& in, const std::vector<double>& values) {
  std::vector<Override> ov = in.overrides;
  for (auto& o : calib::overrides_for(in.params, values)) ov.push_back(std::move(o));
  return ov;
}

/// The search's work items on `ex`: each finished item's bytes kept in the store before the search uses them; no
/// further item handed out once the caller cancels.
calib::Runner executor_runner(const Executor& ex, const Hooks& hooks, const EvaluationStore& store) {
  calib::Runner r;
  r.run = [&ex, &hooks, &store](std::size_t n, const std::function<std::string(std::size_t)>& work,
                                const std::function<void(std::size_t, std::string, int)>& done) {
    auto take = [&](std::size_t i, std::string bytes, int rank) {
      if (store.keep && !bytes.empty()) store.keep(bytes);  // before the search uses it: a kill after this loses nothing
      done(i, std::move(bytes), rank);
      return !hooks.cancel_requested();
    };
    // At least one thread, also for no items: every rank must ask the deciding one once to learn that there is nothing.
    const int jobs = std::max(1, job_count(ex.jobs, n));
    if (ex.distribute) return ex.distribute(n, jobs, work, take);
    run_parallel(n, jobs, work, [&](std::size_t i, std::string bytes) { return take(i, std::move(bytes), ex.rank); });
  };
  r.share = [&ex](std::string& bytes) {
    if (ex.share) ex.share(bytes);
  };
  return r;
}

/// Hooks.progress after each evaluation, one call at a time.
class EvaluationCount {
 public:
  EvaluationCount(const Hooks& hooks, std::size_t total) : hooks_(hooks), total_(total) {}
  void add() {
    if (!hooks_.progress) return;
    std::lock_guard lock(mu_);
    ++done_;
    total_ = std::max(total_, done_);
    hooks_.progress(done_, total_);
  }
  /// The last call: everything done.
  void finish() {
    if (!hooks_.progress) return;
    std::lock_guard lock(mu_);
    hooks_.progress(done_, done_);
  }

 private:
  const Hooks& hooks_;
  std::size_t done_ = 0, total_;
  std::mutex mu_;
};

/// A trajectory's fitted run, for best.csv and its summary's blocks; none for a table, without a best or when it
/// fails (best_run_error says why). A run that scores otherwise than the search did is kept with a warning.
void add_fitted_run(const CalibrationInputs& in, CalibrationResult& r) {
  const calib::SearchResult& res = r.search;
  if (!res.best_eval.ok || !in.trajectory()) return;
  try {
    r.best_run = simulate(calib::trajectory_scene(*in.window, in.scene_path, with_values(in, res.best)), false, Recording::kinematics);
    // The same run the search scored: the same objective (best.csv shows what was fitted).
    const double again = calib::trajectory_objective(std::get<MeasuredTrajectory>(in.data), *in.window, *r.best_run).objective;
    if (!(std::abs(again - res.best_eval.objective) <= 1e-9 * res.best_eval.objective)) {
      std::ostringstream os;
      os << "the fitted run scored again gives objective " << again << " against the search's " << res.best_eval.objective
         << "; best.csv holds the run made again";
      r.best_run_warning = os.str();
    }
  } catch (const std::exception& e) {
    r.best_run_error = e.what();
  }
}

}  // namespace

StageTimes::StageTimes() { end.fill(NAN); }

double StageTimes::wall(calib::Stage s) const {
  const auto i = static_cast<std::size_t>(s);
  if (!std::isfinite(end[i])) return NAN;
  double from = 0;
  for (std::size_t k = 0; k < i; ++k)
    if (std::isfinite(end[k])) from = std::max(from, end[k]);
  return end[i] - from;
}

std::size_t evaluation_budget(std::size_t d, const calib::SearchOptions& opt) {
  const std::size_t scan = opt.scan < 0 ? 8 * d + 1 : static_cast<std::size_t>(opt.scan);
  const std::size_t local = static_cast<std::size_t>(std::max(0, opt.starts)) * static_cast<std::size_t>(std::max(0, opt.max_evals));
  const std::size_t per_point = d > 1 ? static_cast<std::size_t>(std::max(10, opt.max_evals / 4)) : 1;  // as the search's profiles
  const std::size_t points = static_cast<std::size_t>(std::max(0, opt.profile_points));
  const std::size_t edges = points > 0 ? static_cast<std::size_t>(std::max(0, opt.refine)) * 2 * d : 0;
  return scan + 1 + local + (d * points + edges) * per_point;
}

void sort_evaluations(calib::SearchResult& r) {
  std::stable_sort(r.evaluations.begin(), r.evaluations.end(), [](const calib::EvaluationRecord& a, const calib::EvaluationRecord& b) {
    if (a.stage != b.stage) return a.stage < b.stage;
    return a.item < b.item;
  });
}

calib::Evaluation score(const CalibrationInputs& in, const calib::Measurement& m, const std::optional<calib::TrajectoryWindow>& w,
                        const std::vector<double>& values) {
  try {
    const auto ov = with_values(in, values);
    if (const auto* t = std::get_if<MeasuredTrajectory>(&m)) return calib::evaluate_trajectory(*t, *w, in.scene_path, ov);
    return calib::evaluate_table(std::get<MeasuredTable>(m), in.scene_path, ov);
  } catch (const std::exception& e) {
    calib::Evaluation ev;
    ev.objective = ev.rms = INFINITY;
    ev.message = e.what();
    return ev;
  }
}

CalibrationResult run_calibration(const CalibrationInputs& in, const Executor& ex, const Hooks& hooks, const CalibrationWatch& watch,
                                  const EvaluationStore& store) {
  CalibrationResult r;
  r.jobs = job_count(ex.jobs, 1u << 20);  // threads a process (each stage uses at most one per work item)
  r.ranks = ex.ranks;
  EvaluationCount count(hooks, evaluation_budget(in.params.size(), in.search));
  auto evaluate = [&](const std::vector<double>& values) {
    if (store.find)
      if (auto held = store.find(values)) {
        count.add();
        return *held;
      }
    calib::Evaluation e = score(in, in.data, in.window, values);
    if (watch.evaluated) watch.evaluated(e.wall_s);
    count.add();
    return e;
  };
  std::vector<double> start;
  for (const auto& s : in.start) start.push_back(s.value);
  const auto t0 = WallClock::now();
  const calib::Progress items = [&](calib::Stage s, std::size_t done, std::size_t n, std::size_t evaluations, double best) {
    r.stage_times.end[static_cast<std::size_t>(s)] = seconds_since(t0);
    if (watch.items) watch.items(s, done, n, evaluations, best);
  };
  // The runs on this thread (the local search's, the fitted run, the validation) see the caller's stop request and
  // leave its progress meter to Hooks::progress. The caller's cancel, or that stop: the search hands out no more.
  WorkScope scope(run_control(hooks));
  const StopToken stop = this_thread_work().stop;
  const calib::Stopped stopped = [&hooks, stop] { return hooks.cancel_requested() || stop.stop_requested(); };
  r.search = calib::search(in.params, start, evaluate, in.search, executor_runner(ex, hooks, store), items, stopped);
  r.wall_s = seconds_since(t0);
  r.cancelled = r.search.stopped;
  if (!ex.deciding()) return r;
  sort_evaluations(r.search);
  if (!r.cancelled) {
    add_fitted_run(in, r);
    if (in.held_out && r.search.best_eval.ok) r.validation = score(in, *in.held_out, in.held_window, r.search.best);
  }
  count.finish();
  return r;
}

}  // namespace imcol::study
