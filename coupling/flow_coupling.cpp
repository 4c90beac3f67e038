// SPDX-License-Identifier: BSD-3-Clause
#include "coupling/flow_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/timing.hpp"
#include "coupling/divergence_watch.hpp"
#include "coupling/preconditioner_bins.hpp"
#include "coupling/run_cost.hpp"
#include "coupling/step_rule.hpp"
#include "flow/cost.hpp"
#include "flow/fft_size.hpp"

namespace imcol::coupling {

FlowCoupling::FlowCoupling(model::CollisionModel& model, const Scene& sc) : model_(model), sc_(sc) {
  n_ = sc.spheres.size();
  for (std::size_t m = 0; m < n_; ++m) {
    radius_[m] = 0.5 * sc.spheres[m].diameter;
    volume_[m] = 4.0 / 3.0 * std::numbers::pi * std::pow(radius_[m], 3);
  }
  D_ = sc.spheres[0].diameter;
  rho_ = sc.fluid->density;
  u_ref_ = 0;
  for (const auto& s : sc.spheres) u_ref_ = std::max(u_ref_, std::abs(s.velocity));
}

FlowCoupling::~FlowCoupling() = default;

FlowCoupling::Predicted FlowCoupling::predict(double t, std::span<const double> y, double dt) const {
  // Second-order Taylor step from the ODE state; the solid contact force is left out (a contact lasts microseconds,
  // far less than a flow step, and H ≈ 1 there): the kernel sees the rebound one step later.
  Predicted p;
  std::array<double, 2> z{}, u{};
  model_.sphere_states(y, z, u);
  const auto a = model_.accelerations_without_contact(t, y);
  for (std::size_t m = 0; m < n_; ++m) {
    p.z[m] = z[m] + u[m] * dt + 0.5 * a[m] * dt * dt;
    p.u[m] = u[m] + a[m] * dt;
  }
  p.gap = gap_of(p.z);
  return p;
}

double FlowCoupling::gap_of(const std::array<double, 2>& z) const {
  if (n_ == 2) return z[1] - z[0] - radius_[0] - radius_[1];
  if (sc_.wall) return sc_.wall->position - z[0] - radius_[0];
  return std::numeric_limits<double>::infinity();
}

std::vector<flow::SphereState> FlowCoupling::frame_spheres(const Predicted& p, double frame_z, double frame_u) {
  std::vector<flow::SphereState> s(n_);
  const double h = stats_.h;
  if (n_ == 2) {
    // Keep the midpoint of the centres; hold the gap at min_gap_cells·h or more (the rings would overlap).
    const double g_min = sc_.flow.min_gap_cells * h;
    const double gap = std::max(p.gap, g_min);
    if (p.gap < g_min) ++stats_.min_gap_clamped_steps;
    const double mid = 0.5 * (p.z[0] + p.z[1]) - frame_z, c = radius_[0] + radius_[1] + gap;
    // With the gap held, the kernel's spheres move together at the midpoint's velocity: their velocities must
    // match the geometry it sees (a relative velocity across a held gap would squeeze a film that does not thin).
    const double u_mid = 0.5 * (p.u[0] + p.u[1]);
    const bool held = p.gap < g_min;
    s[0] = {radius_[0], mid - 0.5 * c, (held ? u_mid : p.u[0]) - frame_u};
    s[1] = {radius_[1], mid + 0.5 * c, (held ? u_mid : p.u[1]) - frame_u};
  } else if (sc_.wall) {
    // The same rule against the wall: the kernel's sphere stops min_gap_cells·h short of it, at rest with it.
    const double g_min = sc_.flow.min_gap_cells * h;
    const bool held = p.gap < g_min;
    if (held) ++stats_.min_gap_clamped_steps;
    const double z = held ? sc_.wall->position - radius_[0] - g_min : p.z[0];
    s[0] = {radius_[0], z - frame_z, (held ? 0.0 : p.u[0]) - frame_u};
  } else {
    s[0] = {radius_[0], p.z[0] - frame_z, p.u[0] - frame_u};
  }
  return s;
}

std::array<double, 2> FlowCoupling::step_kernel(const Predicted& p, double dt) {
  stop_.throw_if_requested();
  // The frame follows the spheres' midpoint (one sphere: its centre), so the grid never loses them; with a wall
  // it is the lab (the wall is fixed in the grid, which spans the sphere's path).
  const double mid = sc_.wall ? frame_z_ : (n_ == 2 ? 0.5 * (p.z[0] + p.z[1]) : p.z[0]);
  const double new_u = (mid - frame_z_) / dt;
  const double a_frame = (new_u - frame_u_) / dt;
  stats_.frame_travel += std::abs(mid - frame_z_);
  frame_z_ = mid;
  frame_u_ = new_u;
  kernel_->set_stream(-frame_u_);
  const auto t0 = WallClock::now();
  flow::StepInfo info;
  const std::vector<flow::SphereState> imposed = frame_spheres(p, frame_z_, frame_u_);
  try {
    info = kernel_->step(imposed);
  } catch (const SolverError& e) {
    std::ostringstream os;  // the kernel counts time from its start-up; the run from the collision's t = 0
    os << "coupled run, flow step to t = " << kernel_->time() + dt - t_pre_ << " s: " << e.what();
    throw SolverError(os.str());
  } catch (const std::exception& e) {
    std::ostringstream os;
    os << "coupled run, flow step to t = " << kernel_->time() + dt - t_pre_ << " s: the flow kernel failed: " << e.what()
       << " (raise flow.ahead / flow.behind / flow.r_max, or shorten solver.t_end)";
    throw SolverError(os.str());
  }
  stats_.flow_seconds += seconds_since(t0);
  stats_.krylov_iterations += info.krylov_iterations;
  stats_.q_applications = kernel_->q_applications();
  stats_.preconditioner_blocks = kernel_->preconditioner_blocks_built();
  stats_.max_krylov_iterations = std::max(stats_.max_krylov_iterations, info.krylov_iterations);
  stats_.max_krylov_residual = std::max(stats_.max_krylov_residual, info.krylov_residual);
  stats_.max_slip = std::max(stats_.max_slip, info.slip);
  const double courant = kernel_->max_courant();
  stats_.max_courant = std::max(stats_.max_courant, courant);
  u_fluid_ = courant * stats_.h / dt;
  // Lab force: the frame's buoyancy-like term ρ V a_frame (flow/solver.hpp set_stream); then the model's added mass
  // estimate is removed with the kernel's own acceleration of the sphere over the step.
  const model::AddedMassMatrix M = model_.implicit_added_mass(p.gap);
  std::array<double, 2> a_flow{}, f{};
  for (std::size_t m = 0; m < n_; ++m) {
    const double u_imposed = imposed[m].u + frame_u_;  // lab velocity the kernel gave sphere m
    a_flow[m] = (u_imposed - kernel_u_[m]) / dt;
    kernel_u_[m] = u_imposed;
  }
  for (std::size_t m = 0; m < n_; ++m) {
    const double F_lab = info.force[m] + rho_ * volume_[m] * a_frame;
    const double MA_a = (m == 0 ? M.m11 : M.m22) * a_flow[m] + (n_ == 2 ? M.m12 * a_flow[1 - m] : 0.0);
    f[m] = F_lab + MA_a;
  }
  return f;
}

FlowCoupling::StartUp FlowCoupling::plan_start_up() {
  const auto& fs = sc_.flow;
  StartUp su;
  su.h = D_ / fs.cells_per_diameter;
  su.u_mid = n_ == 2 ? 0.5 * (sc_.spheres[0].velocity + sc_.spheres[1].velocity) : sc_.spheres[0].velocity;
  const FlowStep step = flow_step(sc_, su.h);
  su.dt = step.dt;
  step_ = step;
  adapt_.emplace(sc_, su.h, step);
  stats_.cfl = step.cfl;
  double t_pre = su.dt;  // impulsive: one prescribed step
  if (fs.start == FlowStart::developed) {
    if (fs.developed_time > 0) t_pre = fs.developed_time;
    else if (u_ref_ > 0) t_pre = fs.developed_distance * D_ / u_ref_;  // the faster sphere travels that far
  }
  // The start-up's flow steps, counted in double first: a huge developed_time must be refused, not overflow a long.
  const double n_pre_d = std::max(1.0, std::round(t_pre / su.dt));
  if (!(n_pre_d <= 1e8)) {
    std::ostringstream os;
    os << "the developed start would take " << n_pre_d << " flow steps of " << su.dt << " s before t = 0 (more than 1e8)";
    throw InputError(sc_.path, fs.developed_time > 0 ? "flow.developed_time" : "flow.developed_distance", os.str());
  }
  su.n_pre = static_cast<long>(n_pre_d);
  su.t_pre = static_cast<double>(su.n_pre) * su.dt;
  t_pre_ = su.t_pre;
  return su;
}

int FlowCoupling::finest_cells(const StartUp& su, double extent, int multiple) const {
  // Cell counts in double first: a start-up that carries the spheres far (a flow step or a developed start of
  // very long duration) is refused naming its key, not converted to an int that overflows.
  const auto& fs = sc_.flow;
  const double n = multiple * std::ceil(extent / su.h / multiple);
  if (!(n <= 1e6)) {
    double u_max = 0;
    for (std::size_t m = 0; m < n_; ++m) u_max = std::max(u_max, std::abs(sc_.spheres[m].velocity));
    const char* key = su.n_pre >= 2 ? (fs.developed_time > 0 ? "flow.developed_time" : "flow.developed_distance")
                                    : (fs.dt > 0 ? "flow.dt" : "flow.cfl");
    throw InputError(sc_.path, key,
                     "the finest flow level would need " + fmt_number(n) + " cells along one axis (more than 1e6): the spheres travel up to " +
                         fmt_number(u_max * su.t_pre) + " m in the start-up of " + fmt_number(su.t_pre) + " s before t = 0 (" +
                         fmt_number(static_cast<double>(su.n_pre)) + " flow step" + (su.n_pre == 1 ? "" : "s") + " of " +
                         fmt_number(su.dt) + " s)");
  }
  return static_cast<int>(n);
}

flow::Settings FlowCoupling::grid_settings(const StartUp& su) {
  const auto& fs = sc_.flow;
  // Geometry of the finest level in the frame of the midpoint: the largest centre distance over the start-up and
  // the approach, the spheres, and room ahead of and behind the pair (its wake) in the direction of motion.
  double sep = 0;  // centre distance
  if (n_ == 2) {
    const double s0 = sc_.spheres[1].position - sc_.spheres[0].position;
    const double u_rel = sc_.spheres[0].velocity - sc_.spheres[1].velocity;
    sep = std::max(s0, s0 + u_rel * su.t_pre) + 0.25 * D_;
  }
  double dir = su.u_mid >= 0 ? 1.0 : -1.0;
  if (n_ == 1 && su.u_mid == 0 && sc_.has(Effect::gravity))
    dir = (sc_.spheres[0].density - rho_) * sc_.gravity >= 0 ? 1.0 : -1.0;
  const double a_max = std::max(radius_[0], radius_[1]);
  const double front = 0.5 * sep + a_max + fs.ahead * D_, back = 0.5 * sep + a_max + fs.behind * D_;
  const double z_lo = dir > 0 ? -back : -front, z_hi = dir > 0 ? front : back;
  flow::Settings s;
  s.nu = sc_.fluid->viscosity / rho_;
  s.density = rho_;
  s.dt = su.dt;
  s.theta = fs.theta;
  s.h = su.h;
  // r_max is in units of sphere 1's D; a larger target gets the same room relative to its own size.
  const double r_finest = std::max(fs.r_max * D_, fs.r_max * 2 * a_max);
  s.nr = finest_cells(su, r_finest, 2);
  s.nz = flow::fft_friendly_cells(finest_cells(su, z_hi - z_lo, 4), 4);
  s.levels = fs.levels;
  s.z_center = 0.5 * (z_lo + z_hi);
  s.u_inf = -su.u_mid;
  s.krylov_tol = fs.krylov_tol;
  s.krylov_max_iter = fs.krylov_max_iter;
  s.krylov_restart = fs.krylov_restart;
  s.ring_spacing = fs.ring_spacing;
  s.preconditioner_bins = fs.preconditioner_bins;
  s.block_probe_stride = fs.block_probe_stride;
  stats_.dt = su.dt;
  stats_.h = su.h;
  stats_.nr = s.nr;
  stats_.levels = s.levels;
  stats_.cells_per_diameter = fs.cells_per_diameter;
  stats_.pre_steps = su.n_pre;
  // The frame moves with the midpoint at u_mid, from where it was at the start-up's beginning.
  const double mid0 = n_ == 2 ? 0.5 * (sc_.spheres[0].position + sc_.spheres[1].position) : sc_.spheres[0].position;
  frame_z_ = mid0 - su.u_mid * su.t_pre;
  frame_u_ = su.u_mid;
  if (sc_.wall) {  // the lab frame; the finest level from behind the sphere's start to beyond the wall
    frame_z_ = 0;
    frame_u_ = 0;
    const double a = radius_[0];
    const double z_start = std::min(sc_.spheres[0].position, sc_.spheres[0].position - sc_.spheres[0].velocity * su.t_pre);
    const double lo = z_start - a - fs.behind * D_, hi = sc_.wall->position + fs.ahead * D_;
    s.z_center = 0.5 * (lo + hi);
    s.nz = flow::fft_friendly_cells(finest_cells(su, hi - lo, 4), 4);
    s.u_inf = 0;
    s.wall_z = sc_.wall->position;
  }
  stats_.nz = s.nz;
  return s;
}

std::array<double, 2> FlowCoupling::start_up_travel(const StartUp& su) const {
  // Each sphere's travel relative to the grid over the start-up (the grid follows the midpoint, or is the lab).
  std::array<double, 2> travel{};
  for (std::size_t m = 0; m < n_; ++m) {
    const double u_grid = sc_.wall ? 0.0 : su.u_mid;
    travel[m] = std::abs(sc_.spheres[m].velocity - u_grid) * su.t_pre;
  }
  return travel;
}

FlowCoupling::Predicted FlowCoupling::prescribed(double t) const {
  // The spheres on their constant-velocity paths before t = 0.
  Predicted p;
  for (std::size_t m = 0; m < n_; ++m) {
    p.z[m] = sc_.spheres[m].position + sc_.spheres[m].velocity * t;
    p.u[m] = sc_.spheres[m].velocity;
  }
  p.gap = gap_of(p.z);
  return p;
}

std::array<double, 2> FlowCoupling::develop_flow(const StartUp& su, const flow::Settings& s) {
  report_start_up(0, su.n_pre, "allocating the grid");
  try {
    kernel_ = std::make_unique<flow::Solver>(s, frame_spheres(prescribed(-su.t_pre), frame_z_, frame_u_));
  } catch (const std::exception& e) {
    throw InputError(sc_.path, "flow", std::string("the flow grid cannot be built: ") + e.what());
  }
  stats_.bytes = kernel_->bytes();
  // The kernel's fluid starts at rest; the first prescribed step sets the spheres moving (its force is discarded).
  for (std::size_t m = 0; m < n_; ++m) kernel_u_[m] = 0.0;
  std::array<double, 2> f{};
  long step_now = 0;
  if (progress_ || stop_.stop_possible())
    kernel_->set_block_progress([&](long col, long n) {
      stop_.throw_if_requested();
      if (progress_) report_start_up(step_now, su.n_pre, "force system block " + std::to_string(col) + "/" + std::to_string(n));
    });
  for (long k = 1; k <= su.n_pre; ++k) {
    step_now = k;
    report_start_up(k, su.n_pre, "");
    f = step_kernel(prescribed(-su.t_pre + static_cast<double>(k) * su.dt), su.dt);
  }
  kernel_->set_block_progress(nullptr);
  if (stop_.stop_possible()) kernel_->set_block_progress([this](long, long) { stop_.throw_if_requested(); });  // later solves
  return f;
}

void FlowCoupling::reset_step_stats() {
  stats_.flow_seconds = 0;
  stats_.krylov_iterations = 0;
  stats_.max_krylov_iterations = 0;
  stats_.max_slip = 0;
  stats_.max_krylov_residual = 0;
  stats_.max_courant = 0;
  stats_.min_gap_clamped_steps = 0;
  stats_.frame_travel = 0;
}

void FlowCoupling::start_up() {
  const auto t0 = WallClock::now();
  const StartUp su = plan_start_up();
  flow::Settings s = grid_settings(su);
  s.preconditioner_bins = preconditioner_bins(s, su);
  check_cost(s, su.dt, su.n_pre, start_up_travel(su));
  start_up_began_ = t0;
  const std::array<double, 2> f = develop_flow(su, s);
  // After a developed start the last prescribed step is a steady one: its force is f_rest at t = 0.
  have_f_rest_ = su.n_pre >= 2;
  f_rest_ = f;
  start_force_ = f;
  stats_.pre_seconds = seconds_since(t0);
  stats_.pre_q_applications = kernel_->q_applications();
  reset_step_stats();  // the start-up's kernel statistics are not the run's
}

int FlowCoupling::preconditioner_bins(const flow::Settings& s, const StartUp& su) const {
  if (sc_.flow.preconditioner_bins > 0) return sc_.flow.preconditioner_bins;
  // The later blocks of the spheres that move relative to the grid (all but a lone free sphere, which the grid
  // follows): each bin costs their applications of Q.
  double columns = 0;
  if (n_ == 2 || sc_.wall)
    for (std::size_t m = 0; m < n_; ++m) columns += flow::later_block_applications(s, flow::ring_points(s, 2 * radius_[m]));
  return automatic_bins(flow_steps_to_end(su.dt), columns, s.krylov_tol);  // the start-up's steps revisit the blocks' own offsets
}

double FlowCoupling::run_end() const {
  return expected_.end > 0 ? std::min(expected_.end, sc_.solver.t_end) : sc_.solver.t_end;
}

double FlowCoupling::flow_steps_to_end(double dt) const {
  const double end = run_end();
  const auto& e = expected_;
  if (!adapt_ || !adapt_->active() || e.t.size() < 2) return std::ceil(end / dt * (1 - 1e-12));
  // The adaptive step's own choices along the path (the sample at or before each flow time; the fluid's own speed is
  // not known before the run), to its end, then steps of the last one.
  AdaptiveStep a(sc_, stats_.h > 0 ? stats_.h : D_ / sc_.flow.cells_per_diameter, step_);
  double t = 0, steps = 0;
  std::size_t i = 0;
  while (t < end && steps < 1e8) {
    while (i + 1 < e.t.size() && e.t[i + 1] <= t) ++i;
    if (i + 1 >= e.t.size()) break;
    const auto z = std::span<const double>(e.z[i].data(), n_), u = std::span<const double>(e.u[i].data(), n_);
    t += a.next(z, u, 0.0, model_.blend(gap_of(e.z[i])) > 0);
    ++steps;
  }
  if (t < end) steps += std::ceil((end - t) / a.dt());
  return steps;
}

double FlowCoupling::snapshots_to_end() const {
  const auto& e = expected_;
  double gap = std::numeric_limits<double>::infinity();
  for (const auto& z : e.z) gap = std::min(gap, gap_of(z));
  double n = 1;                                      // the end's
  if (e.z.empty() || gap <= D_) n += 1;              // gap 1 D (unknown path: counted)
  if (e.z.empty() || e.t_contact) n += 1;            // contact
  if (e.z.empty() || (e.t_separation && *e.t_separation + sc_.measure.window <= run_end())) n += 1;  // after separation
  if (sc_.flow.fields_every > 0) n += std::floor(run_end() / sc_.flow.fields_every) + 1;
  return n;
}

void FlowCoupling::check_cost(const flow::Settings& s, double dt, long n_pre, const std::array<double, 2>& travel) {
  CoupledCostInput in;
  in.settings = s;
  for (std::size_t m = 0; m < n_; ++m) {
    in.diameters.push_back(2 * radius_[m]);
    in.start_up_travel.push_back(travel[m]);
    in.moves_after.push_back(n_ == 2 || sc_.wall.has_value());  // a free sphere stays at the grid's centre
  }
  in.start_up_steps = n_pre;
  in.steps = flow_steps_to_end(dt);
  if (sc_.flow.fields && sink_) in.snapshots = snapshots_to_end();
  const CoupledCost c = coupled_cost(in);
  stats_.est_start_up_s = c.start_up_s;
  stats_.est_blocks_s = c.blocks_s;
  stats_.est_steps_s = c.steps_s;
  stats_.est_fields_s = c.fields_s;
  stats_.est_bytes = c.grid.bytes;
  stats_.est_q_applications = c.q_applications;
  stats_.est_steps = in.steps;
  stats_.est_field_snapshots = in.snapshots;
  est_before_t0_s_ = c.before_t0_s();
  if (const std::string why = flow::memory_refusal(c.grid); !why.empty())
    throw InputError(sc_.path, "flow.cells_per_diameter", "the flow grid " + why + ": use fewer cells per diameter or levels");
  const double hours = c.total_s() / 3600;
  if (hours > sc_.flow.max_wall_hours) {
    std::ostringstream os;
    os << std::setprecision(3) << "the coupled run may take an estimated " << hours << " hours (start-up " << c.start_up_s / 3600
       << " h: " << n_pre << " flow steps before t = 0; force system blocks " << c.blocks_s / 3600 << " h; up to " << in.steps
       << " flow steps " << c.steps_s / 3600 << " h; steps of " << dt << " s on " << c.grid.vertices
       << " vertices), more than flow.max_wall_hours = " << sc_.flow.max_wall_hours
       << ": raise flow.dt or flow.cfl, lower flow.cells_per_diameter, flow.levels, the start-up (flow.developed_distance, "
          "flow.developed_time) or solver.t_end, or raise flow.max_wall_hours";
    throw InputError(sc_.path, "flow.max_wall_hours", os.str());
  }
}

void FlowCoupling::report_start_up(long step, long n_pre, const std::string& doing) {
  if (!progress_) return;
  const double run = seconds_since(start_up_began_);
  // Time left: the estimate until two steps are done, then the measured rate (which includes the blocks built).
  const double left = step >= 2 ? run / double(step - 1) * double(n_pre - step + 1) : std::max(0.0, est_before_t0_s_ - run);
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << "flow start-up: step " << step << "/" << n_pre << ", " << (doing.empty() ? "" : doing + ", ")
     << run << " s, ~" << left << " s left (whole run est. " << stats_.est_total_s() << " s)";
  progress_(os.str());
}

flow::SnapshotFrame FlowCoupling::lab_frame() const {
  flow::SnapshotFrame f{frame_z_, frame_u_, -t_pre_, {}};
  for (std::size_t m = 0; m < n_; ++m) f.trajectory.push_back({radius_[m], traj_z_[m], traj_u_[m]});
  return f;
}

void FlowCoupling::note_trajectory(std::span<const double> y) { model_.sphere_states(y, traj_z_, traj_u_); }

void FlowCoupling::take_snapshot(const std::string& name, const std::string& label) {
  series_->take(*kernel_, lab_frame(), name, label);
  ++stats_.field_snapshots;
  stats_.fields_seconds = series_->seconds();
}

void FlowCoupling::take_regular() {
  std::ostringstream name, label;
  name << "fields_" << std::setw(6) << std::setfill('0') << stats_.steps;
  label << "flow step " << stats_.steps << ",";
  take_snapshot(name.str(), label.str());
}

void FlowCoupling::maybe_snapshot(double t, double gap) {
  if (!series_) return;
  bool took = false;
  auto take = [&](const char* name, const std::string& label) {
    take_snapshot(name, label + ",");
    took = true;
  };
  if (std::isfinite(gap) && !snap_gap_ && gap <= D_) {
    snap_gap_ = true;
    take("flow_gap_1D", "gap 1 D");
  }
  if (!snap_contact_ && model_.t_contact()) {
    snap_contact_ = true;
    take("flow_contact", "contact");
  }
  if (!snap_after_ && model_.t_separation() && t >= *model_.t_separation() + sc_.measure.window * (1 - 1e-9)) {
    snap_after_ = true;
    take("flow_after_separation", "one fit window after separation");
  }
  // The regular snapshots: at the first step at or past each multiple of flow.fields_every (one per step; a step
  // that took a named snapshot already has its fields).
  const double every = sc_.flow.fields_every;
  if (every > 0 && t >= next_every_ * (1 - 1e-12)) {
    if (!took) take_regular();
    next_every_ = (std::floor(t / every * (1 + 1e-12)) + 1) * every;
  }
}

void FlowCoupling::start_series() {
  // The flow fields are computed only when something writes them (a file sink): sweeps and comparisons skip them.
  if (sc_.flow.fields && sink_) series_.emplace(sc_.flow.fields_format, sink_);
  if (series_ && sc_.flow.fields_every > 0) {  // the flow the spheres start in
    take_regular();
    next_every_ = sc_.flow.fields_every;
  }
}

void FlowCoupling::finish_series() {
  if (!series_) return;
  take_snapshot("flow_end", "end of run,");
  series_->finish();
  stats_.fields_seconds = series_->seconds();
}

double FlowCoupling::advance(Integrator& integ, const DivergenceWatch& watch, double t1) {
  double t = 0;
  const auto t0 = WallClock::now();
  try {
    t = integ.advance(t1);
  } catch (const SolverError& e) {
    // A contact at an impossible speed (contact.delta_ss) or a stalled integrator after the flow fed the spheres
    // energy: name the flow coupling first (the integrator's facts kept).
    if (watch.energy_exceeded(integ.state())) throw SolverError(watch.energy_message(integ.time(), integ.state(), e.what()), e);
    throw;
  } catch (const std::exception& e) {
    if (watch.energy_exceeded(integ.state())) throw SolverError(watch.energy_message(integ.time(), integ.state(), e.what()));
    throw;
  }
  stats_.ode_seconds += seconds_since(t0);
  return t;
}

SolverStats FlowCoupling::run(const IntegratorSettings& st, Observer& observer) {
  const double cpu0 = thread_cpu_seconds();
  start_up();
  Integrator integ(model_, st, observer);
  DivergenceWatch watch(model_, sc_, integ.state(), step_);
  // The start-up's last force is the one the spheres first feel: a kernel that diverged while the flow developed
  // shows here, before the integrator turns it into an impossible impact.
  watch.check_kernel_force(0.0, stats_.dt, acting(start_force_, integ.state()), integ.state());
  double t = 0;
  long n = 0;
  double t_base = 0, t_target = 0;  // the flow times are t_base + k Δt since the step last changed
  long n_base = 0;
  stats_.dt_min = stats_.dt_max = stats_.dt;
  note_trajectory(integ.state());
  start_series();
  while (!integ.finished()) {
    const double dt_old = kernel_->settings().dt, dt = next_step(integ.state());
    if (dt != dt_old) {
      t_base = t_target;
      n_base = n;
    }
    const double t1 = t_target = t_base + static_cast<double>(n + 1 - n_base) * dt;
    const Predicted p = predict(t, integ.state(), dt);
    const auto f1 = step_kernel(p, dt);
    watch.check_kernel_force(t, dt, acting(f1, integ.state()), integ.state());
    model::SimulatedForce sf;
    sf.t0 = t;
    sf.t1 = t1;
    sf.f1 = f1;
    sf.f0 = (have_f_rest_ && sc_.flow.force_in_step == ForceInStep::linear) ? f_rest_ : f1;
    model_.set_simulated_force(sf);
    if (sf.f0 != f_rest_ || n == 0) integ.reinit();  // the force jumps at t_n: restart the method there
    f_rest_ = f1;
    have_f_rest_ = true;
    std::array<double, 2> z0{}, u0{};
    model_.sphere_states(integ.state(), z0, u0);
    const double t_start = t;
    t = advance(integ, watch, t1);
    ++n;
    stats_.steps = n;
    watch.check_step(t_start, t, u0, integ.state());
    stats_.max_energy_ratio = watch.max_energy_ratio();
    note_trajectory(integ.state());
    maybe_snapshot(t, gap_of(traj_z_));
    if (t < t1 - 1e-12 * std::max(1.0, t1) && !integ.finished())
      throw SolverError("coupling: the integrator stopped at t = " + std::to_string(t) + " s before the flow step's end");
  }
  finish_series();
  stats_.dt_min = adapt_->dt_min();
  stats_.dt_max = adapt_->dt_max();
  stats_.step_changes = adapt_->changes();
  stats_.cpu_seconds = thread_cpu_seconds() - cpu0;
  return integ.stats();
}

double FlowCoupling::next_step(std::span<const double> y) {
  if (!adapt_->active()) return kernel_->settings().dt;
  std::array<double, 2> z{}, u{};
  model_.sphere_states(y, z, u);
  const bool blended = model_.blend(gap_of(z)) > 0;
  const double dt = adapt_->next(std::span<const double>(z.data(), n_), std::span<const double>(u.data(), n_), u_fluid_, blended);
  kernel_->set_dt(dt);
  return dt;
}

std::array<double, 2> FlowCoupling::acting(const std::array<double, 2>& f, std::span<const double> y) const {
  std::array<double, 2> z{}, u{};
  model_.sphere_states(y, z, u);
  const double w = 1 - model_.blend(gap_of(z));  // f_SIM's weight, 1 − H
  return {w * f[0], w * f[1]};
}

}  // namespace imcol::coupling
