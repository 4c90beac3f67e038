// SPDX-License-Identifier: BSD-3-Clause
#include "apps/work_precision.hpp"
#include "apps/work_precision_flow.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "apps/cluster.hpp"
#include "apps/format.hpp"
#include "apps/plot.hpp"
#include "apps/rank_inputs.hpp"
#include "apps/run_failure.hpp"
#include "run/simulate.hpp"
#include "model/collision_model.hpp"
#include "core/errors.hpp"
#include "core/report.hpp"

namespace imcol {

namespace fs = std::filesystem;

namespace {

/// One integrator × evaluator combination and its ladder.
struct Config {
  std::string integrator;  // cvode-dense | cvode-gmres | ida
  std::string evaluator;   // none | soe-step | soe | direct
  std::string label() const { return evaluator == "none" ? integrator : integrator + " / " + evaluator; }
};

struct Point {
  Config cfg;
  double rtol = NAN, direct_step = NAN, history_tol = NAN;
  bool ok = false;
  std::string message;
  double e = NAN, err_e = NAN, err_traj = NAN, ms = NAN;
  long steps = 0, rhs = 0, lin_iters = 0;
};

/// Output samples (events excluded) keyed by time: the gap (or z1) over D and the velocities.
using Samples = std::map<double, std::vector<double>>;  // time → (gap or z1)/D, u1[, u2]

Samples samples(const RunResult& r, double D) {
  auto col = [&](const std::string& name) {
    for (std::size_t i = 0; i < r.columns.size(); ++i)
      if (r.columns[i] == name) return static_cast<long>(i);
    return -1L;
  };
  const long ig = col("gap") >= 0 ? col("gap") : col("z1"), iu1 = col("u1"), iu2 = col("u2"), ie = col("event");
  Samples s;
  for (const auto& row : r.rows) {
    if (row[ie] != 0.0) continue;
    std::vector<double> v = {row[ig] / D, row[iu1]};
    if (iu2 >= 0) v.push_back(row[iu2]);
    s[row[0]] = v;
  }
  return s;
}

/// max over common output times of max(|Δgap|/D, |Δu|/u_scale); NaN if no common times.
double trajectory_error(const Samples& run, const Samples& ref, double u_scale) {
  double err = 0;
  std::size_t common = 0;
  for (const auto& [t, v] : run) {
    auto it = ref.lower_bound(t - 1e-12 * std::max(1.0, std::abs(t)));
    if (it == ref.end() || std::abs(it->first - t) > 1e-12 * std::max(1.0, std::abs(t))) continue;
    ++common;
    err = std::max(err, std::abs(v[0] - it->second[0]));
    for (std::size_t k = 1; k < v.size(); ++k) err = std::max(err, std::abs(v[k] - it->second[k]) / u_scale);
  }
  return common ? err : NAN;
}

double metric_of(const RunResult& r, bool collision) {
  return (collision ? r.summary.e : r.summary.u1_final_m_s).value_or(NAN);
}


/// Least-squares slope of log10(y) against log10(x).
std::optional<double> loglog_slope(const std::vector<std::pair<double, double>>& xy) {
  if (xy.size() < 3) return std::nullopt;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (auto [x, y] : xy) {
    const double lx = std::log10(x), ly = std::log10(y);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double n = static_cast<double>(xy.size()), d = n * sxx - sx * sx;
  if (!(std::abs(d) > 0)) return std::nullopt;
  return (n * sxy - sx * sy) / d;
}

/// The history evaluators to compare (all three by default where the scene has history; "none" without it); checks
/// the integrators too.
std::vector<std::string> evaluators_for(const WorkPrecisionOptions& opt, bool history) {
  std::vector<std::string> evaluators = opt.evaluators;
  if (evaluators.empty()) evaluators = history ? std::vector<std::string>{"soe-step", "soe", "direct"} : std::vector<std::string>{"none"};
  for (const auto& e : evaluators) {
    if (e != "soe" && e != "soe-step" && e != "direct" && e != "none")
      throw InputError("--evaluators", e, "unknown evaluator (expected soe, soe-step, direct)");
    if (e != "none" && !history)
      throw InputError("--evaluators", e, "the scene has no history effect (list it in `effects`, or pass --add-history)");
  }
  for (const auto& i : opt.integrators)
    if (i != "cvode-dense" && i != "cvode-gmres" && i != "ida")
      throw InputError("--integrators", i, "unknown integrator (expected cvode-dense, cvode-gmres, ida)");
  return evaluators;
}

/// Every evaluator with every integrator; a combination the solvers cannot do goes to `skipped` with its reason.
std::vector<Config> configs_for(const std::vector<std::string>& evaluators, const WorkPrecisionOptions& opt,
                                std::vector<std::string>& skipped) {
  std::vector<Config> configs;
  for (const auto& ev : evaluators)
    for (const auto& in : opt.integrators) {
      if (in == "cvode-gmres" && ev != "soe") {
        skipped.push_back(in + (ev == "none" ? "" : " / " + ev) +
                          ": gmres needs the memory modes of the soe history evaluator (its preconditioner)");
        continue;
      }
      configs.push_back({in, ev});
    }

  return configs;
}

/// The table of every rung against the reference.
void print_table(const std::string& name, const WorkPrecisionOptions& opt, bool history, const std::string& metric, double e_ref,
                 double ref_unc, double u_scale, const std::vector<std::string>& skipped, const std::vector<Point>& pts) {
  std::cout << "scene " << name << ": work-precision, median of " << opt.repeat << " runs per setting (atol = rtol"
            << (history ? "; soe fit tolerance = rtol within [1e-10, 1e-3]" : "") << ")\n";
  std::cout << "reference: cvode dense, rtol = atol = " << opt.ref_rtol
            << (history ? ", soe fit tolerance " + sci(opt.ref_history_tol, 0) : std::string()) << ": " << metric << " = "
            << std::setprecision(12) << e_ref << "; its uncertainty ~ " << sci(ref_unc) << "\n";
  std::cout << "trajectory error: max over output times of |d gap|/D and |d u|/" << sci(u_scale, 3) << " m/s\n";
  for (const auto& s : skipped) std::cout << "skipped " << s << "\n";
  std::cout << std::left << std::setw(22) << "integrator / history" << std::right << std::setw(9) << "rtol" << std::setw(11)
            << "direct dt" << std::setw(16) << metric << std::setw(10) << "err " + metric << std::setw(10) << "err traj"
            << std::setw(11) << "median ms" << std::setw(8) << "steps" << std::setw(8) << "rhs" << "\n";
  for (const auto& p : pts) {
    std::cout << std::left << std::setw(22) << p.cfg.label() << std::right << std::setw(9) << sci(p.rtol, 0) << std::setw(11)
              << sci(p.direct_step, 1);
    if (p.ok)
      std::cout << std::setw(16) << std::fixed << std::setprecision(11) << p.e << std::setw(10) << sci(p.err_e, 1) << std::setw(10)
                << sci(p.err_traj, 1) << std::setw(11) << std::setprecision(3) << p.ms << std::setw(8) << p.steps << std::setw(8)
                << p.rhs << "\n";
    else
      std::cout << "  " << p.message << "\n";
  }
}

void check_options(const WorkPrecisionOptions& opt) {
  if (opt.repeat < 1) throw InputError("--repeat", "repeat", "must be >= 1");
  if (opt.rtols.empty()) throw InputError("--rtols", "rtols", "give at least one tolerance");
  for (double r : opt.rtols)
    if (!(r >= 1e-14 && r < 1)) throw InputError("--rtols", "rtols", "each tolerance must lie in [1e-14, 1)");
  if (!(opt.ref_rtol >= 1e-14 && opt.ref_rtol < 1)) throw InputError("--ref-rtol", "ref_rtol", "must lie in [1e-14, 1)");
  if (!(opt.direct_rtol >= 1e-14 && opt.direct_rtol < 1)) throw InputError("--direct-rtol", "direct_rtol", "must lie in [1e-14, 1)");
  if (!(opt.ref_history_tol >= 1e-13 && opt.ref_history_tol < 0.1))
    throw InputError("--ref-history-tolerance", "ref_history_tolerance", "must lie in [1e-13, 0.1)");
  for (double h : opt.direct_steps)
    if (!(h >= kDirectStepMin && h <= kDirectStepMax))
      throw InputError("command line", "--direct-steps", "each multiple must lie in [" + fmt_number(kDirectStepMin) + ", " +
                                                            fmt_number(kDirectStepMax) + "] (got " + fmt_number(h) + ")");
}

/// Per configuration, the slopes of log error against log rtol (or the direct step) and against log steps, over
/// errors above `floor`; printed and returned for the JSON file.
nlohmann::ordered_json observed_orders(const std::vector<Config>& configs, const std::vector<Point>& pts, double floor) {
  nlohmann::ordered_json orders = nlohmann::ordered_json::object();
  std::cout << "observed order (fits over errors above " << sci(floor, 0) << "): err ~ rtol^a (tolerance proportionality), err ~ steps^-p\n";
  for (const auto& c : configs) {
    std::vector<std::pair<double, double>> by_tol, by_steps;
    for (const auto& p : pts)
      if (p.cfg.label() == c.label() && p.ok && p.err_e > floor) {
        by_tol.push_back({c.evaluator == "direct" ? p.direct_step : p.rtol, p.err_e});
        by_steps.push_back({static_cast<double>(p.steps), p.err_e});
      }
    const auto a = loglog_slope(by_tol), q = loglog_slope(by_steps);
    const std::string x = c.evaluator == "direct" ? "direct_step" : "rtol";
    std::cout << "  " << std::left << std::setw(22) << c.label() << std::right << " err ~ " << x << "^"
              << (a ? fixed(*a, 2) : std::string("n/a")) << "   p = " << (q ? fixed(-*q, 2) : std::string("n/a"))
              << "   (" << by_tol.size() << " points)\n";
    orders[c.label()] = {{"vs", x}, {"exponent", a ? nlohmann::ordered_json(*a) : nullptr},
                         {"order_in_steps", q ? nlohmann::ordered_json(-*q) : nullptr}, {"points", by_tol.size()}};
  }
  return orders;
}

/// For errors 1e-3, 1e-6, 1e-9: the fastest setting that reaches it and keeps it at every tighter rung.
nlohmann::ordered_json cheapest_settings(const std::vector<Point>& pts, const std::string& metric) {
  nlohmann::ordered_json cheapest = nlohmann::ordered_json::object();
  std::cout << "cheapest setting that reaches an error in " << metric << " (and keeps it at every tighter rung):\n";
  for (double target : {1e-3, 1e-6, 1e-9}) {
    const Point* best = nullptr;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      bool good = pts[i].ok && pts[i].err_e <= target;
      for (std::size_t j = i + 1; good && j < pts.size() && pts[j].cfg.label() == pts[i].cfg.label(); ++j)
        good = pts[j].ok && pts[j].err_e <= target;
      if (good && (!best || pts[i].ms < best->ms)) best = &pts[i];
    }
    std::cout << "  " << sci(target, 0) << ": ";
    if (best) {
      std::cout << best->cfg.label() << ", rtol " << sci(best->rtol, 0)
                << (std::isnan(best->direct_step) ? "" : ", direct_step " + sci(best->direct_step)) << " (" << std::fixed
                << std::setprecision(3) << best->ms << " ms, error " << sci(best->err_e, 1) << ")\n";
      cheapest[sci(target, 0)] = {{"config", best->cfg.label()}, {"rtol", best->rtol},
                                  {"direct_step_s", std::isnan(best->direct_step) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(best->direct_step)},
                                  {"median_ms", best->ms}, {"error", best->err_e}};
    } else {
      std::cout << "not reached\n";
      cheapest[sci(target, 0)] = nullptr;
    }
  }

  return cheapest;
}

std::string points_csv(const std::vector<Point>& pts, const std::string& metric) {
  std::ostringstream csv;
  csv << std::setprecision(12);
  csv << "integrator,evaluator,rtol,atol,direct_step_s,history_tolerance,status," << metric << ",err_" << metric
      << ",err_trajectory,median_wall_ms,steps,rhs_evals,lin_iters,message\n";
  for (const auto& p : pts) {
    std::string msg = p.message;
    std::replace(msg.begin(), msg.end(), ',', ';');
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    csv << p.cfg.integrator << "," << p.cfg.evaluator << "," << csv_number(p.rtol) << "," << csv_number(p.rtol) << "," << csv_number(p.direct_step)
        << "," << csv_number(p.history_tol) << "," << (p.ok ? "ok" : "failed") << "," << csv_number(p.e) << "," << csv_number(p.err_e) << ","
        << csv_number(p.err_traj) << "," << csv_number(p.ms) << "," << p.steps << "," << p.rhs << "," << p.lin_iters << "," << msg << "\n";
  }
  return csv.str();
}

/// The base scene with one configuration's solver and history settings; atol = rtol.
Scene scene_for(const Scene& base, const Config& c, double rtol, double direct_step, double history_tol) {
  Scene sc = base;
  sc.solver.rtol = rtol;
  sc.solver.atol = rtol;
  sc.solver.integrator = c.integrator == "ida" ? IntegratorMethod::ida : IntegratorMethod::cvode;
  sc.solver.linear_solver = c.integrator == "cvode-gmres" ? LinearSolverChoice::gmres : LinearSolverChoice::dense;
  if (c.evaluator != "none") {
    sc.history.evaluator = *choice_from_string<HistoryEvaluator>(c.evaluator);
    if (c.evaluator == "soe" || c.evaluator == "soe-step") {
      sc.history.modes = 0;
      sc.history.tolerance = history_tol;
    } else {
      sc.history.direct_step = direct_step;
    }
  }
  return sc;
}

/// The soe fit tolerance follows rtol (within what the fit supports), so that one knob sets the accuracy.
double history_tol_for(double rtol) { return std::clamp(rtol, 1e-10, 1e-3); }

/// The direct evaluator's base step: the scene's, or the model's automatic step (read off a model built, not run).
double direct_base_step(const Scene& base, const std::vector<std::string>& evaluators) {
  double h_direct = base.history.direct_step;
  if (std::count(evaluators.begin(), evaluators.end(), "direct") && !(h_direct > 0)) {
    Scene probe = base;
    probe.history.evaluator = HistoryEvaluator::direct;
    h_direct = model::CollisionModel(probe).history_options().direct_step;
  }
  return h_direct;
}

/// One setting of a ladder: rtol along --rtols, or for the direct evaluator its step at --direct-rtol.
struct Rung {
  Config cfg;
  double rtol = NAN, direct_step = NAN;
  double history_tol() const { return cfg.evaluator == "soe" || cfg.evaluator == "soe-step" ? history_tol_for(rtol) : NAN; }
};

std::vector<Rung> ladder_rungs(const std::vector<Config>& configs, const WorkPrecisionOptions& opt, double h_direct) {
  std::vector<Rung> rungs;
  for (const auto& c : configs) {
    if (c.evaluator == "direct")
      for (double m : opt.direct_steps) rungs.push_back({c, opt.direct_rtol, m * h_direct});
    else
      for (double r : opt.rtols) rungs.push_back({c, r, NAN});
  }
  return rungs;
}

/// The runs of the command, numbered: 0 is the reference (the tightest settings), then each rung's --repeat runs
/// (1 + rung * repeat + k). Each is an independent run (apps/cluster.hpp hands them out, one at a time per rank).
struct Runs {
  Config ref_cfg;
  std::vector<Rung> rungs;
  int repeat = 1;
  std::size_t count() const { return 1 + rungs.size() * static_cast<std::size_t>(repeat); }
  const Rung& rung(std::size_t i) const { return rungs[(i - 1) / static_cast<std::size_t>(repeat)]; }
  int k(std::size_t i) const { return static_cast<int>((i - 1) % static_cast<std::size_t>(repeat)); }
};

/// What one run tells: its wall time; for the reference and each rung's last run its metric, solver counts and
/// output samples. A run that threw says how (`failure`): a SolverError fails its rung (or, the reference's, the
/// command); anything else ends the command.
struct RunOutcome {
  RunFailure failure;
  double metric = NAN, wall_s = NAN;
  std::int64_t steps = 0, rhs = 0, lin_iters = 0;
  Samples samples;
  std::string solver_json, effects_json;  // the reference's solver block and effects as in its summary.json
};

/// A run's outcome as bytes (another rank's runs reach rank 0 so): plain doubles, which arrive bit for bit.
std::string encode(const RunOutcome& o) {
  std::string s;
  auto put = [&](auto v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); };
  auto put_str = [&](const std::string& x) {
    put(static_cast<std::uint64_t>(x.size()));
    s += x;
  };
  put(static_cast<std::int32_t>(o.failure.kind));
  for (const auto* x : {&o.failure.what, &o.failure.where, &o.failure.key, &o.failure.problem, &o.solver_json, &o.effects_json}) put_str(*x);
  put(o.metric), put(o.wall_s), put(o.steps), put(o.rhs), put(o.lin_iters);
  put(static_cast<std::uint64_t>(o.samples.size()));
  for (const auto& [t, v] : o.samples) {
    put(t);
    put(static_cast<std::uint64_t>(v.size()));
    for (double x : v) put(x);
  }
  return s;
}

RunOutcome decode(const std::string& s) {
  std::size_t at = 0;
  auto get = [&](auto& v) {
    std::memcpy(&v, s.data() + at, sizeof v);
    at += sizeof v;
  };
  auto get_str = [&](std::string& x) {
    std::uint64_t n = 0;
    get(n);
    x.assign(s, at, n);
    at += n;
  };
  RunOutcome o;
  std::int32_t kind = 0;
  get(kind);
  o.failure.kind = kind;
  for (auto* x : {&o.failure.what, &o.failure.where, &o.failure.key, &o.failure.problem, &o.solver_json, &o.effects_json}) get_str(*x);
  get(o.metric), get(o.wall_s), get(o.steps), get(o.rhs), get(o.lin_iters);
  std::uint64_t n = 0;
  get(n);
  for (std::uint64_t r = 0; r < n; ++r) {
    double t = 0;
    std::uint64_t m = 0;
    get(t), get(m);
    std::vector<double> v(m);
    for (double& x : v) get(x);
    o.samples.emplace(t, std::move(v));
  }
  return o;
}

/// Runs run i of `runs` (on whichever rank it was handed to).
RunOutcome run_one(const Scene& base, const WorkPrecisionOptions& opt, const Runs& runs, bool collision, double D, std::size_t i) {
  RunOutcome o;
  try {
    const bool ref = i == 0;
    const Scene sc = ref ? scene_for(base, runs.ref_cfg, opt.ref_rtol, NAN, opt.ref_history_tol)
                         : scene_for(base, runs.rung(i).cfg, runs.rung(i).rtol, runs.rung(i).direct_step, runs.rung(i).history_tol());
    const RunResult r = simulate(sc);
    o.wall_s = r.summary.wall_time_s;
    if (ref || runs.k(i) == runs.repeat - 1) {  // every run of a rung gives the same numbers: its last run's are kept
      const SolverStats& sol = r.summary.solver.stats;
      o.metric = metric_of(r, collision);
      o.steps = sol.steps, o.rhs = sol.rhs_evals, o.lin_iters = sol.lin_iters;
      o.samples = samples(r, D);
    }
    if (ref) {
      o.solver_json = r.summary_json["solver"].dump();
      o.effects_json = nlohmann::json(r.summary.effects).dump();
    }
  } catch (const std::exception&) {
    o.failure = RunFailure::current();
  }
  return o;
}

/// The reference run's metric, its samples and the velocity scale of trajectory errors.
struct Reference {
  Config cfg;
  RunOutcome run;
  double value = NAN;
  double u_scale = 0;
};

Reference reference_of(const Config& cfg, RunOutcome run, bool collision) {
  Reference ref;
  ref.cfg = cfg;
  ref.run = std::move(run);
  ref.value = ref.run.metric;
  if (std::isnan(ref.value))
    throw SolverError("the reference run has no " + std::string(collision ? "e (no collision by t_end?)" : "final velocity"));
  for (const auto& [t, v] : ref.run.samples)
    for (std::size_t k = 1; k < v.size(); ++k) ref.u_scale = std::max(ref.u_scale, std::abs(v[k]));
  if (!(ref.u_scale > 0)) ref.u_scale = 1;
  return ref;
}

/// One rung from its --repeat runs: their median wall time and the errors against the reference. A run's solver
/// failure (the first in run order) fails the rung.
Point point_of(const Runs& runs, std::size_t r, const std::vector<RunOutcome>& outcomes, const Reference& ref, bool collision) {
  const Rung& g = runs.rungs[r];
  Point p;
  p.cfg = g.cfg;
  p.rtol = g.rtol;
  p.direct_step = g.direct_step;
  p.history_tol = g.history_tol();
  std::vector<double> times;
  for (int k = 0; k < runs.repeat; ++k) {
    const RunOutcome& o = outcomes[1 + r * static_cast<std::size_t>(runs.repeat) + static_cast<std::size_t>(k)];
    if (o.failure.kind == RunFailure::solver) {
      p.message = "solver failure: " + o.failure.what;
      return p;
    }
    times.push_back(o.wall_s);
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  const RunOutcome& last = outcomes[(r + 1) * static_cast<std::size_t>(runs.repeat)];
  p.ok = true;
  p.e = last.metric;
  p.err_e = std::abs(p.e - ref.value);
  p.err_traj = trajectory_error(last.samples, ref.run.samples, ref.u_scale);
  p.ms = 1e3 * times[times.size() / 2];
  p.steps = last.steps;
  p.rhs = last.rhs;
  p.lin_iters = last.lin_iters;
  if (std::isnan(p.e)) p.message = collision ? "no e (no collision by t_end)" : "no final velocity";
  return p;
}

/// The progress line of a run (stderr): the reference's, or a rung's before its first run.
void progress_line(const WorkPrecisionOptions& opt, const Runs& runs, std::size_t i, const std::string& where) {
  if (i == 0) {
    std::cerr << "reference run (cvode dense, rtol = atol = " << opt.ref_rtol << ")" << where << "\n";
    return;
  }
  const Rung& g = runs.rung(i);
  std::cerr << "  " << g.cfg.label() << "  rtol " << sci(g.rtol, 0) << (std::isnan(g.direct_step) ? "" : "  direct_step " + sci(g.direct_step))
            << where << "\n";
}

/// The reference and every rung's runs, spread over the MPI job's ranks (one run at a time per rank, so that wall
/// times are not shared with another run of this command) or, without MPI, run one after the other. Rank 0 returns
/// the outcome of every run and the runs each rank ran; other ranks return nothing. A failed reference, or a run that
/// threw anything but a SolverError, stops the hand-out and is rethrown here (on rank 0).
std::vector<RunOutcome> run_all(const Scene& base, const WorkPrecisionOptions& opt, const Runs& runs, bool collision, double D,
                                std::vector<int>& runs_by_rank) {
  const cluster::World w = cluster::world();
  const std::size_t n = runs.count();
  std::vector<RunOutcome> outcomes(n);
  std::vector<std::exception_ptr> thrown(n);  // set by the thread that ran it, read after all have joined
  std::vector<int> arrived(runs.rungs.size(), 0);
  runs_by_rank.assign(static_cast<std::size_t>(w.size), 0);
  std::size_t stop = n;  // the first run that ends the command
  auto work = [&](std::size_t i) {
    if (w.size == 1 && (i == 0 || runs.k(i) == 0)) progress_line(opt, runs, i, "");
    RunOutcome o = run_one(base, opt, runs, collision, D, i);
    if (o.failure.thrown) thrown[i] = o.failure.thrown;  // this process's run: rank 0 rethrows the exception itself
    return encode(o);
  };
  auto done = [&](std::size_t i, std::string bytes, int rank) {
    outcomes[i] = decode(bytes);
    ++runs_by_rank[static_cast<std::size_t>(rank)];
    if (w.size > 1) {
      if (i == 0) progress_line(opt, runs, i, " (on rank " + std::to_string(rank) + ")");
      else if (++arrived[(i - 1) / static_cast<std::size_t>(runs.repeat)] == runs.repeat)
        progress_line(opt, runs, i, (runs.repeat > 1 ? " (its last run on rank " : " (on rank ") + std::to_string(rank) + ")");
    }
    const int f = outcomes[i].failure.kind;
    if (f != RunFailure::none && (i == 0 || f != RunFailure::solver)) {
      stop = std::min(stop, i);
      return false;
    }
    return i > 0 || !std::isnan(outcomes[0].metric);  // a reference without its metric ends the command too
  };
  if (w.rank > 0) {
    cluster::run_distributed(n, 1, work, {});
    return {};
  }
  cluster::run_distributed(n, 1, work, done);
  if (stop < n) {
    outcomes[stop].failure.thrown = thrown[stop];
    outcomes[stop].failure.rethrow();
  }
  return outcomes;
}

/// The reference's own uncertainty, estimated as the error of the same settings one decade looser than the
/// reference (the tightest cvode-dense rung).
double reference_uncertainty(const std::vector<Point>& pts, const WorkPrecisionOptions& opt, const Reference& ref) {
  double ref_unc = 0;
  for (const auto& p : pts)
    if (p.ok && p.cfg.integrator == "cvode-dense" && p.cfg.evaluator == ref.cfg.evaluator && p.rtol == *std::min_element(opt.rtols.begin(), opt.rtols.end()))
      ref_unc = p.err_e;
  return ref_unc;
}

}  // namespace

int work_precision(const std::string& scene_path, const std::vector<Override>& overrides, const WorkPrecisionOptions& opt) {
  check_options(opt);
  Scene base = load_scene(scene_path, overrides);
  const fs::path fallback = fs::path("out") / (base.name + "-work_precision");
  if (base.has(Effect::flow)) {  // a coupled scene: the ladder is the grid and the flow step
    FlowLadderOptions fo;
    fo.out = opt.out;
    return work_precision_flow(base, overrides, fo, fallback);
  }
  if (!opt.ladder_options.empty())
    throw InputError("command line", opt.ladder_options.front(),
                     "work-precision sets rtol = atol along --rtols and the integrator along --integrators: give them there");
  if (opt.add_history) {
    if (!base.fluid) throw InputError(scene_path, "fluid", "--add-history needs a [fluid] table");
    base.effects.insert(Effect::history);
  }
  const bool history = base.has(Effect::history);
  const std::vector<std::string> evaluators = evaluators_for(opt, history);
  const bool collision = base.has_target();
  const double D = base.spheres[0].diameter;

  // Configurations; a combination the solvers cannot do is skipped with its reason.
  std::vector<std::string> skipped;
  const std::vector<Config> configs = configs_for(evaluators, opt, skipped);
  // The reference (the tightest settings) is run 0, then every rung's runs. The direct evaluator's accuracy is set
  // by its step: its ladder varies the step at a tight rtol.
  Runs runs;
  runs.ref_cfg = {"cvode-dense", history ? "soe" : "none"};
  runs.rungs = ladder_rungs(configs, opt, direct_base_step(base, evaluators));
  runs.repeat = opt.repeat;
  // Under mpirun, ranks > 0 run what rank 0 hands them (docs/cluster.md); rank 0 alone writes and prints.
  const int ranks = cluster::world().size;
  if (const int differ = cluster::agree(work_precision_inputs(base, opt))) return differ;  // ranks on other inputs: refused
  std::optional<OutputUnit> unit;
  if (const int refused = cluster::on_rank0([&] { unit.emplace(opt.out, fallback, base.path); })) return refused;
  std::vector<int> runs_by_rank;
  std::vector<RunOutcome> outcomes = run_all(base, opt, runs, collision, D, runs_by_rank);
  if (cluster::world().rank > 0) return 0;
  const Reference ref = reference_of(runs.ref_cfg, std::move(outcomes[0]), collision);
  std::vector<Point> pts;
  for (std::size_t r = 0; r < runs.rungs.size(); ++r) pts.push_back(point_of(runs, r, outcomes, ref, collision));
  // Fits exclude errors within 10x of the reference's own uncertainty.
  const double ref_unc = reference_uncertainty(pts, opt, ref);
  const double floor = std::max(10 * ref_unc, 1e-15);
  const double e_ref = ref.value, u_scale = ref.u_scale;
  const Config& ref_cfg = ref.cfg;

  // Table.
  const std::string metric = collision ? "e" : "u_end";
  print_table(base.name, opt, history, metric, e_ref, ref_unc, u_scale, skipped, pts);

  // Observed orders and the cheapest settings.
  const nlohmann::ordered_json orders = observed_orders(configs, pts, floor);
  const nlohmann::ordered_json cheapest = cheapest_settings(pts, metric);

  // Files.
  nlohmann::ordered_json j;
  j["scene"] = base.name;
  j["metric"] = metric;
  j["reference"] = {{"integrator", "cvode-dense"}, {"evaluator", ref_cfg.evaluator}, {"rtol", opt.ref_rtol}, {"atol", opt.ref_rtol},
                    {"history_tolerance", history ? nlohmann::ordered_json(opt.ref_history_tol) : nullptr},
                    {"value", e_ref}, {"uncertainty", ref_unc}, {"wall_time_s", ref.run.wall_s},
                    {"solver", nlohmann::ordered_json::parse(ref.run.solver_json)}};  // the reference run's solver block as in its summary.json
  j["trajectory_velocity_scale_m_s"] = u_scale;
  j["repeat"] = opt.repeat;
  j["skipped"] = skipped;
  j["observed_order"] = orders;
  j["cheapest"] = cheapest;
  j["effects"] = nlohmann::ordered_json::parse(ref.run.effects_json);
  if (ranks > 1) {
    j["ranks"] = ranks;
    j["runs_by_rank"] = runs_by_rank;
  }
  j["run"] = unit->run();
  write_file_atomic(unit->dir() / "work_precision.csv", points_csv(pts, metric));
  write_file_atomic(unit->dir() / "work_precision.json", j.dump(2) + "\n");
  if (opt.plot) run_plot_script("plot_work_precision.py", *unit, "work_precision.png");
  unit->commit();
  std::cout << "wrote " << (unit->target() / "work_precision.csv").string() << " and " << (unit->target() / "work_precision.json").string() << "\n";
  return 0;
}

}  // namespace imcol
