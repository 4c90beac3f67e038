// SPDX-License-Identifier: BSD-3-Clause
#include "run/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "core/errors.hpp"
#include "model/impact_speed.hpp"

namespace imcol::run {

using model::Evaluation;
using model::SphereForces;

namespace {

/// The flow effect's per-sphere columns, after the terms' (model/force_term.hpp TermSlot::column).
struct FlowColumn {
  const char* name;
  double SphereForces::*field;
};
constexpr FlowColumn kFlowColumns[] = {{"f_sim", &SphereForces::f_sim}, {"f_thr", &SphereForces::f_thr}};

}  // namespace

double measure_interval(const model::CollisionModel& model, const Scene& sc) {
  const double dt = sc.output.dt;
  if (!model.has_target()) return dt;
  const double u = model::impact_speed_bound(sc, model.geometry());
  if (!(u > 0)) return dt;
  // The contact_ends window; for a start inside the contact zone, which shortens the zone to the initial gap, at most the
  // time to cross that gap: the liquid film there can brake the rebound within a small part of the window.
  const double distance = sc.measure.ends_distance * 2 * model.radius(0);
  const double window = (model.started_in_contact() ? std::min(distance, model.delta_ss_m()) : distance) / u;
  const double n = std::ceil(dt * sc.measure.samples_per_window / window);
  const double interval = n > 1 ? dt / n : dt;
  // Every sample is kept (56 bytes) and costs an interpolation: refuse a run that would take too many.
  const double count = sc.solver.t_end / interval;
  if (count > sc.measure.max_samples) {
    std::ostringstream os;
    os << "the measures would sample the run " << fmt_number(count) << " times (every " << fmt_number(interval)
       << " s up to t_end, " << sc.measure.samples_per_window << " samples per contact_ends window at an impact speed of up to "
       << fmt_number(u) << " m/s), more than measure.max_samples = " << fmt_number(sc.measure.max_samples)
       << ": lower solver.t_end (the samples are counted up to it, even for a run that comes to rest sooner), raise "
       << "measure.ends_distance, lower measure.samples_per_window, or raise measure.max_samples (up to 1e9)";
    // The key named is the one of these the scene changed from its default, else t_end.
    const Scene::Measure defaults{};
    const char* key = sc.measure.samples_per_window != defaults.samples_per_window ? "measure.samples_per_window"
                      : sc.measure.ends_distance != defaults.ends_distance             ? "measure.ends_distance"
                      : sc.measure.max_samples != defaults.max_samples               ? "measure.max_samples"
                                                                                     : "solver.t_end";
    throw InputError(sc.path, key, os.str());
  }
  return interval;
}

Recorder::Recorder(model::CollisionModel& model, const Scene& sc, bool progress, bool forces, double sample_dt)
    : model_(model), sc_(sc), sample_dt_(sample_dt > 0 ? sample_dt : sc.output.dt), next_row_(sc.output.dt), min_gap_(INFINITY), forces_(forces), progress_(progress && ::isatty(2)),
      contact_rows_on_(forces && model.has_target() && sc.has(Effect::elastic) && sc.has(Effect::history)),
      contact_zone_(3 * model.delta_ss_m()) {
  const bool pair = model.n_spheres() == 2;
  columns_ = {"t", "z1", "u1"};
  if (model.has_target()) columns_.push_back("gap");
  if (pair) {
    columns_.push_back("z2");
    columns_.push_back("u2");
  }
  if (model.has_target()) columns_.push_back("u_rel");
  const bool flow = sc.has(Effect::flow);
  for (int m = 1; forces_ && m <= static_cast<int>(model.n_spheres()); ++m) {
    const std::string k = std::to_string(m);
    for (const auto& term : model.terms()) columns_.push_back(term->properties().column + k);
    for (const auto& c : kFlowColumns)
      if (flow) columns_.push_back(c.name + k);
    columns_.push_back("a" + k);
  }
  const auto& slots = model.kind_slots();
  const auto first = [&](model::ForceKind k) -> std::optional<std::size_t> {
    const auto& s = slots[static_cast<std::size_t>(k)];
    return s.empty() ? std::nullopt : std::optional<std::size_t>(s.front());
  };
  contact_slot_ = first(model::ForceKind::contact);  // the contact law's term
  history_slot_ = first(model::ForceKind::history);
  model.keep_step_ends(contact_rows_on_);  // a row at every step near contact: its evaluation is the quadrature's
  // The samples up to t_end (events add a few; a run that would take more than kReserved grows as it goes).
  constexpr double kReserved = 1 << 16;
  track_.reserve(static_cast<std::size_t>(std::min(sc.solver.t_end / sample_dt_, kReserved)) + 8, model.quadrature_size() > 0);
  if (forces_ && sc.has(Effect::flow)) columns_.push_back("H");
  columns_.push_back("event");
}

void Recorder::sample(double t, std::span<const double> y, bool at_event) {
  if (!sampled_) {
    sampled_ = true;
    t0_ = WallClock::now();
  }
  // A row: an event, the first sample, each output time k·output.dt, or a sample off the sampling grid (the last).
  bool row = at_event || rows_.empty();
  const double eps = 1e-6 * sample_dt_;
  if (std::abs(t - std::round(t / sample_dt_) * sample_dt_) > eps) row = true;
  while (t >= next_row_ - eps) {
    row = true;
    next_row_ = static_cast<double>(++k_row_) * sc_.output.dt;
  }
  if (!row) {
    const Evaluation kin = model_.kinematic_state(y);
    if (model_.has_target()) {
      min_gap_ = std::min(min_gap_, kin.gap);
      add_to_track(t, kin);
    }
    if (meter_) meter_->set(t, sc_.solver.t_end);
    if (progress_) show_progress(t);
    return;
  }
  // Without force columns the forces are still needed where the model watches for rest.
  const bool evaluate = forces_ || model_.observes_accelerations();
  const Evaluation ev = evaluate ? model_.evaluate(t, y) : model_.kinematic_state(y);
  if (model_.has_target()) add_to_track(t, ev);
  rows_.push_back(make_row(t, ev, at_event));
  model_.observe(t, ev);  // its watchers may end the run: at rest on the wall, or moving with its partner
  if (meter_) meter_->set(t, sc_.solver.t_end);
  if (progress_) show_progress(t);
  if (model_.has_target()) {
    min_gap_ = std::min(min_gap_, ev.gap);
    if (forces_) max_force_ = std::max(max_force_, std::abs(contact_slot_ ? ev.f[0].term[*contact_slot_] : 0.0));
  }
}

std::vector<double> Recorder::make_row(double t, const Evaluation& ev, bool at_event) {
  // The columns in the order the constructor named them.
  std::vector<double> r(columns_.size());
  double* p = r.data();
  const bool flow = sc_.has(Effect::flow), pair = model_.n_spheres() == 2, target = model_.has_target();
  *p++ = t;
  *p++ = ev.z[0];
  *p++ = ev.u[0];
  if (target) *p++ = ev.gap;
  if (pair) {
    *p++ = ev.z[1];
    *p++ = ev.u[1];
  }
  if (target) *p++ = ev.u_rel;
  const std::size_t terms = model_.terms().size();
  for (std::size_t m = 0; forces_ && m < model_.n_spheres(); ++m) {
    const auto& f = ev.f[m];
    p = std::copy_n(f.term.begin(), terms, p);
    if (flow)
      for (const auto& c : kFlowColumns) *p++ = f.*c.field;
    *p++ = f.accel;
    if (history_slot_) max_history_ = std::max(max_history_, std::abs(f.term[*history_slot_]));
  }
  if (forces_ && flow) *p++ = ev.H;
  *p++ = at_event ? 1.0 : 0.0;
  if (p != r.data() + r.size()) throw std::logic_error("Recorder::make_row: the row does not match the columns");
  return r;
}

void Recorder::step_end(double t, std::span<const double> y) {
  if (!contact_rows_on_) return;
  if (!(model_.gap_of(y) < contact_zone_)) return;
  if (!contact_rows_.empty() && !(t > contact_rows_.back()[0])) return;
  contact_rows_.push_back(model_.with_evaluation(t, y, [&](const model::Evaluation& ev) { return make_row(t, ev, false); }));
}

void Recorder::quadratures(std::span<const double> q) {
  for (std::size_t k = 0; k < work_.size() && k < q.size(); ++k) work_[k] = q[k];
}

void Recorder::add_energies(const Evaluation& ev) {
  track_.work.push_back(work_);
  double ke = 0;
  for (std::size_t m = 0; m < model_.n_spheres(); ++m) ke += 0.5 * model_.mass(static_cast<int>(m)) * ev.u[m] * ev.u[m];
  track_.ke_spheres.push_back(ke);
  const model::AddedMassMatrix M = sc_.has(Effect::added_mass) ? model_.implicit_added_mass(ev.gap) : model::AddedMassMatrix{};
  track_.ke_added.push_back(0.5 * (M.m11 * ev.u[0] * ev.u[0] + M.m22 * ev.u[1] * ev.u[1]) + M.m12 * ev.u[0] * ev.u[1]);
}

void Recorder::add_to_track(double t, const Evaluation& ev) {
  if (!track_.t.empty() && !(t > track_.t.back())) return;  // an event sampled twice (at the same t)
  const bool pair = model_.n_spheres() == 2;
  if (model_.quadrature_size() > 0) add_energies(ev);
  track_.t.push_back(t);
  track_.gap.push_back(ev.gap);
  track_.u.push_back(ev.u_rel);
  track_.z1.push_back(ev.z[0]);
  track_.u1.push_back(ev.u[0]);
  track_.z2.push_back(pair ? ev.z[1] : 0.0);
  track_.u2.push_back(pair ? ev.u[1] : 0.0);
}

void Recorder::finish_progress() {
  if (shown_) std::cerr << "\r" << std::string(160, ' ') << "\r" << std::flush;
}

void Recorder::show_status(const std::string& text) {
  if (!progress_ || seconds_since(start_) < 2.0 || seconds_since(last_) < 0.5) return;
  last_ = WallClock::now();
  shown_ = true;
  std::string line = "\r  " + text;
  if (line.size() < 120) line.resize(120, ' ');
  std::cerr << line << std::flush;
}

void Recorder::show_progress(double t) {
  const double run = seconds_since(start_);
  estimate_.add(seconds_since(t0_), t);  // counted from t = 0 (not the start-up before it)
  if (run < 2.0 || seconds_since(last_) < 0.5) return;
  last_ = WallClock::now();
  shown_ = true;
  std::cerr << "\r  " << progress_text(t, sc_.solver.t_end, steps_, run, estimate_.seconds_left(sc_.solver.t_end)) << "   " << std::flush;
}

std::string progress_text(double t, double t_end, long steps, double elapsed, std::optional<double> left) {
  std::ostringstream os;
  os << "t = " << std::setprecision(4) << t << " s of t_end " << t_end << " s (" << std::fixed << std::setprecision(1)
     << 100 * t / t_end << " %), " << steps << " steps, " << elapsed << " s elapsed";
  if (left) os << ", about " << *left << " s left to t_end";
  return os.str();
}

}  // namespace imcol::run
