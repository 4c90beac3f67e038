// SPDX-License-Identifier: BSD-3-Clause
#include "run/flow_run.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

#include "core/errors.hpp"
#include "core/timing.hpp"
#include "core/work_scope.hpp"
#include "flow/cost.hpp"
#include "flow/solver.hpp"
#include "run/flow_references.hpp"

namespace imcol {

namespace {

/// The options' overrides replace scene keys; each gets the scene key's check (exit 2 naming the option).
void apply_overrides(flow::FlowScene& sc, const FlowRunOptions& opt) {
  auto positive = [](const char* option, const char* key, double v) {
    if (!(std::isfinite(v) && v >= 1e-30 && v <= 1e30))
      throw InputError(std::string("command line (") + option + ")", key, "must be a finite number in [1e-30, 1e30] (got " + fmt_number(v) + ")");
  };
  auto in_range = [](const char* option, const char* key, long v, long lo, long hi) {
    if (v < lo || v > hi)
      throw InputError(std::string("command line (") + option + ")", key,
                       "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + std::to_string(v) + ")");
  };
  if (opt.t_end) positive("--t-end", "time.t_end", *opt.t_end), sc.t_end = *opt.t_end, sc.overridden.insert("--t-end");
  if (opt.dt) positive("--dt", "time.dt", *opt.dt), sc.dt = *opt.dt, sc.overridden.insert("--dt");
  if (opt.cells_per_diameter) {
    in_range("--cells", "grid.cells_per_diameter", *opt.cells_per_diameter, 4, 4096);
    sc.cells_per_diameter = static_cast<int>(*opt.cells_per_diameter);
    sc.overridden.insert("--cells");
  }
  if (opt.levels) {
    in_range("--levels", "grid.levels", *opt.levels, 1, 16);
    sc.levels = static_cast<int>(*opt.levels);
    sc.overridden.insert("--levels");
  }
}

/// Memory and wall time estimated before anything is allocated (flow/cost.hpp): beyond half the physical memory
/// the run is refused; beyond an hour it needs allow_long.
void check_cost(const flow::FlowScene& sc, const FlowRunOptions& opt) {
  const flow::Settings set = sc.settings();
  std::vector<double> diameters;
  bool moving = false;
  for (const auto& p : sc.spheres) {
    diameters.push_back(p.diameter);
    moving = moving || p.velocity != 0 || p.amplitude != 0;
  }
  const flow::CostEstimate c = flow::estimate_cost(set, diameters, moving);
  const double vertices = c.vertices;
  const std::string where = sc.overridden.empty() ? sc.path : "command line (--cells/--levels)";
  if (const std::string why = flow::memory_refusal(c); !why.empty())
    throw InputError(sc.overridden.count("--cells") || sc.overridden.count("--levels") ? where : sc.path, "grid.cells_per_diameter",
                     "the grid " + why + ": use fewer cells or levels");
  const double steps = std::ceil(sc.t_end / sc.dt - 1e-9);
  const double seconds = steps * c.seconds_per_step;
  if (seconds > 3600 && !opt.allow_long)
    throw InputError(sc.overridden.count("--dt") || sc.overridden.count("--t-end") ? "command line (--dt/--t-end)" : sc.path, "time.dt",
                     "an estimated " + fmt_number(seconds / 3600) + " hours (" + fmt_number(steps) + " steps of " + fmt_number(vertices) +
                         " vertices): raise time.dt, lower time.t_end or the grid, or pass --allow-long to run anyway");
}

/// One run: the solver, the references, and what the steps have gathered for the force history and the summary.
class FlowRun {
 public:
  FlowRun(const flow::FlowScene& sc, const FlowRunOptions& opt, const flow::FileSink& files);
  FlowRunResult run();

 private:
  void announce() const;
  void write_csv_header();
  /// Step n; false once a gap has fallen below output.min_gap (the run stops there).
  bool advance(long n);
  void write_csv_row(long n, double t, double wall, double cd, double fsb, const std::vector<flow::SphereState>& next,
                     const flow::StepInfo& info);
  /// One sphere and a wall: f_SIM vs f_THR at the report gaps, the unresolved-gap warning; false: stop.
  bool watch_wall(double t, const std::vector<flow::SphereState>& next, const flow::StepInfo& info);
  /// Several spheres: the unresolved-gap warning; false: stop.
  bool watch_pair_gap(double t, const std::vector<flow::SphereState>& next);
  void progress_line(long n, double t, double wall, double cd, const flow::StepInfo& info) const;
  void take_snapshot();
  /// The typed result but the force history.
  FlowRunResult result(double wall_total) const;
  FlowDragComparison drag_comparison() const;
  FlowOneSphere one_sphere(bool settled) const;
  void add_references(FlowRunResult& r) const;  // gaps, f_SIM vs f_THR, the wall, the oscillating sphere
  FlowGrid grid() const;
  void add_steps_and_solver(FlowRunResult& r, double wall_total) const;

  const flow::FlowScene& sc_;
  const FlowRunOptions& opt_;
  std::optional<flow::FieldSeries> series_;  // with a file sink
  const flow::Settings set_;
  const int nb_;
  const double D_, a_, U_, Re_, mu_, nu_;
  const double q_;  // dynamic pressure × frontal area
  const double drag_sign_, cd_ref_, f_stokes_;
  const long nsteps_;
  const flow::FlowSphere& s0_;
  const bool osc_, wall1_;  // one sphere oscillating in fluid at rest; one sphere and a wall
  // impulsive start: compared over 0.8 ≤ νt/a² ≤ 4 (the window of tests/test_flow_drag.cpp)
  const double basset_t0_, basset_t1_;
  const WallClock::time_point t0_;
  flow::Solver solver_;
  std::unique_ptr<AnalyticPairForce> thr_;
  std::optional<OscillatingSphereForce> f_osc_;
  std::ostringstream hist_;
  // two spheres, or a sphere and a wall: simulated vs reduced-order force at a few gaps (the seed's Fig. 6.4)
  std::vector<double> report_gaps_ = {1.0, 0.5, 0.25, 0.1, 0.05};
  std::vector<FlowGapForces> thr_rows_;
  std::vector<double> cds_, times_, walls_;
  long krylov_total_ = 0;
  int krylov_max_ = 0;
  double slip_max_ = 0, last_cd_ = NAN, min_gap_seen_ = INFINITY;
  std::vector<double> last_force_;
  double last_wall_force_ = 0;
  int snap_ = 0;
  long steps_done_ = 0;
  double basset_err_ = 0, osc_err_ = 0, osc_amp_ = 0;
  bool basset_any_ = false;
  ProgressMeter* const meter_ = this_thread_work().meter;  // flow steps of all
};

FlowRun::FlowRun(const flow::FlowScene& sc, const FlowRunOptions& opt, const flow::FileSink& files)
    : sc_(sc),
      opt_(opt),

      set_(sc.settings()),
      nb_(static_cast<int>(sc.spheres.size())),
      D_(sc.D()),
      a_(0.5 * D_),
      U_(sc.U()),
      Re_(sc.Re()),
      mu_(sc.viscosity),
      nu_(sc.nu()),
      q_(0.5 * sc.density * U_ * U_ * M_PI * a_ * a_),
      drag_sign_((sc.stream - sc.spheres.front().velocity) >= 0 ? 1.0 : -1.0),
      cd_ref_(nb_ == 1 ? flow::standard_drag_coefficient(Re_) : NAN),
      f_stokes_(6 * M_PI * mu_ * a_ * U_),
      nsteps_(std::max(1L, std::lround(std::ceil(sc.t_end / sc.dt - 1e-9)))),
      s0_(sc.spheres.front()),
      osc_(nb_ == 1 && s0_.amplitude != 0 && sc.stream == 0 && s0_.velocity == 0),
      wall1_(nb_ == 1 && sc.wall_position.has_value()),
      basset_t0_(0.8 * a_ * a_ / nu_),
      basset_t1_(4.0 * a_ * a_ / nu_),
      t0_(WallClock::now()),
      solver_(set_, sc.spheres_at(0.0)),
      thr_(nb_ == 2 ? std::make_unique<AnalyticPairForce>(sc) : nullptr),
      last_force_(nb_, 0.0) {
  if (osc_) f_osc_.emplace(mu_, sc.density, a_, s0_.amplitude, s0_.frequency);
  if (files) series_.emplace(sc.fields_format, files);
}

void FlowRun::announce() const {
  if (!opt_.quiet)
    std::cout << "flow " << sc_.name << ": Re = " << Re_ << ", " << sc_.cells_per_diameter << " cells/D, " << set_.levels << " levels of "
              << set_.nr << " x " << set_.nz << " cells, dt = " << sc_.dt << " s, " << nsteps_ << " steps\n";
  double umax = std::abs(sc_.stream);
  for (const auto& p : sc_.spheres) umax = std::max(umax, std::abs(p.velocity) + 2 * M_PI * p.frequency * std::abs(p.amplitude));
  // explicit (AB2) advection: its step limit matters when it is not swamped by the implicit viscous term over a
  // step, i.e. when both the advective CFL U dt/h and U² dt/ν exceed 1 (at Re 0.1 the latter is ~0.04)
  const double cfl = umax * sc_.dt / set_.h, visc = umax * umax * sc_.dt / nu_;
  if (cfl > 1 && visc > 1)
    std::cerr << "imcol: warning: U dt / h = " << cfl << " > 1 and U^2 dt / nu = " << visc
              << " > 1; the explicit (Adams–Bashforth) advection may be unstable\n";
}

void FlowRun::write_csv_header() {
  hist_ << std::setprecision(10);
  hist_ << "step,t,wall_s";
  for (int b = 0; b < nb_; ++b) hist_ << ",z" << b + 1 << ",u" << b + 1 << ",F" << b + 1 << ",F_internal" << b + 1;
  hist_ << ",C_D,C_D_standard,F_stokes_basset,krylov_iterations,slip";
  if (osc_) hist_ << ",F_stokes_oscillating";
  if (nb_ == 2) hist_ << ",gap_D,F_THR1,F_THR2";
  if (sc_.wall_position) hist_ << ",F_wall";
  if (wall1_) hist_ << ",wall_gap_D,F_THR_wall";
  hist_ << "\n";
}

void FlowRun::write_csv_row(long n, double t, double wall, double cd, double fsb, const std::vector<flow::SphereState>& next,
                            const flow::StepInfo& info) {
  hist_ << n << ',' << t << ',' << wall;
  for (int b = 0; b < nb_; ++b) hist_ << ',' << next[b].z << ',' << next[b].u << ',' << info.force[b] << ',' << info.internal[b];
  hist_ << ',' << cd << ',' << cd_ref_ << ',' << fsb << ',' << info.krylov_iterations << ',' << info.slip;
  if (osc_) hist_ << ',' << f_osc_->at(t - 0.5 * sc_.dt);
  if (nb_ == 2) {
    const double gap = next[1].z - next[0].z - next[0].radius - next[1].radius;
    const auto [t1, t2] = thr_->at(next);
    hist_ << ',' << gap / D_ << ',' << t1 << ',' << t2;
  }
  if (sc_.wall_position) hist_ << ',' << info.wall_force;
  if (wall1_)
    hist_ << ',' << (next[0].z - next[0].radius - *sc_.wall_position) / D_ << ',' << brenner_wall_force(mu_, next[0], *sc_.wall_position);
  hist_ << '\n';
}

bool FlowRun::watch_wall(double t, const std::vector<flow::SphereState>& next, const flow::StepInfo& info) {
  const double gap = next[0].z - next[0].radius - *sc_.wall_position;
  while (!report_gaps_.empty() && gap <= report_gaps_.front() * D_) {
    // the sphere's and the wall's delta kernels (3 h wide each) overlap below a 3-cell gap
    thr_rows_.push_back({gap / D_, gap / set_.h, gap >= 3 * set_.h, info.force[0], brenner_wall_force(mu_, next[0], *sc_.wall_position),
                         std::nullopt, std::nullopt, info.wall_force});
    report_gaps_.erase(report_gaps_.begin());
  }
  if (gap < 3 * set_.h && min_gap_seen_ >= 3 * set_.h && !opt_.quiet)
    std::cerr << "imcol: warning: at t = " << t << " the wall gap " << gap / D_ << " D is below 3 cells (h = " << set_.h
              << "): the sphere's and the wall's delta kernels overlap and the force is not resolved (refine the grid)\n";
  min_gap_seen_ = std::min(min_gap_seen_, gap);
  if (sc_.min_gap > 0 && gap < sc_.min_gap * D_) {
    if (!opt_.quiet) std::cout << "  t = " << t << ": wall gap " << gap / D_ << " D < output.min_gap, stop\n";
    return false;
  }
  return true;
}

bool FlowRun::watch_pair_gap(double t, const std::vector<flow::SphereState>& next) {
  double gap = INFINITY;
  for (int b = 0; b + 1 < nb_; ++b) gap = std::min(gap, next[b + 1].z - next[b].z - 0.5 * (sc_.spheres[b].diameter + sc_.spheres[b + 1].diameter));
  if (gap < 3 * set_.h && min_gap_seen_ >= 3 * set_.h && !opt_.quiet)
    std::cerr << "imcol: warning: at t = " << t << " the gap " << gap / D_ << " D is below 3 cells (h = " << set_.h
              << "): the spheres' delta kernels overlap and the forces are not resolved (refine the grid)\n";
  min_gap_seen_ = std::min(min_gap_seen_, gap);
  return !(sc_.min_gap > 0 && gap < sc_.min_gap * D_);
}

void FlowRun::progress_line(long n, double t, double wall, double cd, const flow::StepInfo& info) const {
  if (opt_.quiet || !(n % std::max(1L, nsteps_ / 10) == 0 || n == nsteps_)) return;
  std::cout << "  t = " << std::setw(8) << t << "  C_D = " << std::setw(10) << cd;
  for (int b = 0; b < nb_; ++b) std::cout << "  F" << b + 1 << " = " << std::setw(11) << info.force[b] << " N";
  if (info.krylov_iterations) std::cout << "  gmres " << info.krylov_iterations;
  std::cout << "  (" << std::fixed << std::setprecision(2) << wall << " s)" << std::defaultfloat << std::setprecision(6) << "\n";
}

void FlowRun::take_snapshot() {
  if (series_) series_->take(solver_, {}, std::string("snapshot_") + (snap_ < 10 ? "0" : "") + std::to_string(snap_), "");
  ++snap_;
}

bool FlowRun::advance(long n) {
  const double t = n * sc_.dt;
  const auto next = sc_.spheres_at(t);
  const flow::StepInfo info = solver_.step(next);
  steps_done_ = n;
  const double wall = seconds_since(t0_);
  const double cd = drag_sign_ * info.force[0] / q_;
  const double fsb = impulsive_start_force(mu_, nu_, a_, U_, t);
  if (nb_ == 1 && !osc_ && !sc_.wall_position && Re_ <= 1 && t >= basset_t0_ - 1e-12 * basset_t0_ && t <= basset_t1_ * (1 + 1e-12)) {
    basset_err_ = std::max(basset_err_, std::abs(drag_sign_ * info.force[0] - fsb) / fsb);
    basset_any_ = true;
  }
  if (osc_ && t >= sc_.t_end - 1.0 / s0_.frequency - 1e-12) {  // the last period; step forces are step averages
    osc_err_ = std::max(osc_err_, std::abs(info.force[0] - f_osc_->at(t - 0.5 * sc_.dt)));
    osc_amp_ = std::max(osc_amp_, std::abs(f_osc_->at(t - 0.5 * sc_.dt)));
  }
  cds_.push_back(cd);
  times_.push_back(t);
  walls_.push_back(wall);
  last_cd_ = cd;
  last_force_ = info.force;
  last_wall_force_ = info.wall_force;
  krylov_total_ += info.krylov_iterations;
  krylov_max_ = std::max(krylov_max_, info.krylov_iterations);
  slip_max_ = std::max(slip_max_, info.slip);
  if (n % sc_.history_every == 0 || n == nsteps_) write_csv_row(n, t, wall, cd, fsb, next, info);
  if (nb_ == 2) {
    const double gap = next[1].z - next[0].z - next[0].radius - next[1].radius;
    while (!report_gaps_.empty() && gap <= report_gaps_.front() * D_) {
      const auto [t1, t2] = thr_->at(next);
      // the two spheres' delta kernels (3 h wide each) overlap below a 3-cell gap: f_SIM is not resolved there
      thr_rows_.push_back({gap / D_, gap / set_.h, gap >= 3 * set_.h, info.force[0], t1, info.force[1], t2, std::nullopt});
      report_gaps_.erase(report_gaps_.begin());
    }
  }
  if (wall1_ && !watch_wall(t, next, info)) return false;
  progress_line(n, t, wall, cd, info);
  if (sc_.snapshots > 0 && n == (snap_ + 1) * nsteps_ / sc_.snapshots) take_snapshot();
  return nb_ <= 1 || watch_pair_gap(t, next);
}

FlowRunResult FlowRun::run() {
  announce();
  write_csv_header();
  const StopToken stop = this_thread_work().stop;
  // A step's direct solve builds the force system column by column (long on a fine grid): checked between columns too.
  if (stop.stop_possible()) solver_.set_block_progress([stop](long, long) { stop.throw_if_requested(); });
  for (long n = 1; n <= nsteps_; ++n) {
    stop.throw_if_requested();
    if (meter_) meter_->set(static_cast<double>(n - 1), static_cast<double>(nsteps_));
    if (!advance(n)) break;
  }
  const double wall_total = seconds_since(t0_);
  if (sc_.snapshots > 0 && snap_ < sc_.snapshots) take_snapshot();  // stopped early: one last snapshot
  if (series_) series_->finish();
  FlowRunResult r = result(wall_total);
  r.forces_csv = hist_.str();
  return r;
}

FlowDragComparison FlowRun::drag_comparison() const {
  // the standard (steady) drag curve is a reference only for one sphere at constant velocity whose drag has settled:
  // at least 100 steps, the fluid has passed at least 5 D (t U / D >= 5), and the change over the last tenth of the run,
  // read as the tail of an unsteady-Stokes decay C_D = C_inf + c t^(-1/2) (which changes by 5.4 % of what is left over
  // t in [0.9 t_end, t_end]), leaves less than 0.5 % to come: change < 0.027 %
  const std::size_t k90 = cds_.size() - 1 - (cds_.size() - 1) / 10;
  const double cd_change = cds_.empty() ? NAN : std::abs(last_cd_ - cds_[k90]) / std::abs(last_cd_);
  const double cd_left = cd_change / (1 / std::sqrt(0.9) - 1);
  const double passed_D = steps_done_ * sc_.dt * U_ / D_;
  FlowDragComparison d;
  d.coefficient = last_cd_;
  d.change_last_tenth_percent = 100 * cd_change;
  d.settled = nb_ == 1 && !osc_ && s0_.amplitude == 0 && cds_.size() >= 100 && passed_D >= 5 && cd_left < 0.005;
  d.left_to_settle_percent = 100 * cd_left;
  d.distance_passed_D = passed_D;
  if (d.settled && !std::isnan(cd_ref_)) {
    d.standard = cd_ref_;
    d.error_percent = 100 * (last_cd_ - cd_ref_) / cd_ref_;
  }
  d.stokes_drag_ratio = drag_sign_ * last_force_[0] / f_stokes_;
  return d;
}

FlowOneSphere FlowRun::one_sphere(bool settled) const {
  FlowOneSphere s;
  if (settled && sc_.stream != 0) s.wake_length_D = solver_.wake_length(0) / D_;  // steady runs in a stream only
  // first time after which C_D stays within 3 % of the standard curve
  long k = static_cast<long>(cds_.size());
  while (k > 0 && std::abs(cds_[k - 1] - cd_ref_) <= 0.03 * cd_ref_) --k;
  if (settled && k < static_cast<long>(cds_.size())) {
    s.time_to_3pct_s = times_[k];
    s.wall_time_to_3pct_s = walls_[k];
  }
  if (Re_ <= 1 && !osc_ && basset_any_) s.impulsive_start = FlowImpulsiveStart{basset_t0_, std::min(basset_t1_, steps_done_ * sc_.dt), basset_err_};
  return s;
}

void FlowRun::add_references(FlowRunResult& r) const {
  if (nb_ > 1 || wall1_) r.gap = FlowGapSeen{min_gap_seen_ / D_, min_gap_seen_ >= 3 * set_.h};
  if (nb_ == 2 || wall1_) r.gap_forces = thr_rows_;
  if (sc_.wall_position) r.wall = FlowWall{*sc_.wall_position, last_wall_force_, wall1_};
  if (osc_) r.oscillating = FlowOscillating{f_osc_->delta() / a_, osc_amp_ > 0 ? osc_err_ / osc_amp_ : NAN};
}

FlowGrid FlowRun::grid() const {
  const auto& L0 = solver_.levels().front().g;
  const auto& Lc = solver_.levels().back().g;
  FlowGrid g;
  g.cells_per_diameter = sc_.cells_per_diameter;
  g.h = set_.h;
  g.levels = set_.levels;
  g.nr = set_.nr;
  g.nz = set_.nz;
  g.finest = {L0.r(L0.nr), L0.z0, L0.z(L0.nz)};
  g.coarsest = {Lc.r(Lc.nr), Lc.z0, Lc.z(Lc.nz)};
  g.body_points = solver_.points().size();
  return g;
}

void FlowRun::add_steps_and_solver(FlowRunResult& r, double wall_total) const {
  r.dt = sc_.dt;
  r.theta = sc_.theta;
  r.steps = steps_done_;
  r.t_end = steps_done_ * sc_.dt;
  r.wall_time_s = wall_total;
  r.ms_per_step = 1e3 * wall_total / std::max(1L, steps_done_);
  r.memory_bytes = solver_.bytes();
  r.force_solver = {sc_.krylov_tol, steps_done_ ? double(krylov_total_) / steps_done_ : 0.0, krylov_max_, slip_max_};
}

FlowRunResult FlowRun::result(double wall_total) const {
  FlowRunResult r;
  r.scene = sc_.path;
  r.name = sc_.name;
  r.Re = Re_;
  r.drag = drag_comparison();
  if (nb_ == 1) r.one_sphere = one_sphere(r.drag.settled);
  r.forces_N = last_force_;
  add_references(r);
  r.grid = grid();
  add_steps_and_solver(r, wall_total);
  return r;
}

}  // namespace

FlowRunResult run_flow_scene(flow::FlowScene scene, const FlowRunOptions& opt, const flow::FileSink& files) {
  apply_overrides(scene, opt);
  flow::check_flow_scene(scene);
  check_cost(scene, opt);
  return FlowRun(scene, opt, files).run();
}

}  // namespace imcol
