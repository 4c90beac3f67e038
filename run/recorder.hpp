// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Samples a collision run into trajectory rows (one per output time and event) with the force terms of the
// effects that ran (or, for sweeps, the kinematics alone), lets the model observe each row (it may end the
// run: at rest), and shows progress. The measures of e read their own track: the integrator samples at the
// measures' interval (measure_interval, a divisor of output.dt) and every sample is kept, so that no named
// measure depends on output.dt. Between steps it ends the run when this thread's work was asked to stop, and at each
// sample it sets the work's progress meter (core/work_scope.hpp).
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "model/collision_model.hpp"
#include "run/bounces.hpp"
#include "core/scene.hpp"
#include "core/system.hpp"
#include "core/timing.hpp"
#include "core/work_scope.hpp"
#include "run/progress_estimate.hpp"

namespace imcol::run {

/// The interval (s) at which the integrator samples a run: output.dt divided by the smallest whole number that brings it
/// to at most the contact_ends window at an upper bound of the impact speed over measure.samples_per_window.
double measure_interval(const model::CollisionModel& model, const Scene& sc);

/// The progress line's text: "t = … s of t_end … s (… %), N steps, … s elapsed, about … s left to t_end" (no "left" part
/// without an estimate).
std::string progress_text(double t, double t_end, long steps, double elapsed, std::optional<double> left);

class Recorder : public Observer {
 public:
  /// `progress`: a run still going after 2 s shows a progress line on stderr (a terminal only). `forces`: the rows
  /// carry the force terms and accelerations; without, only the kinematic columns and the event flag.
  /// `sample_dt`: the integrator's sampling interval (measure_interval); rows are kept every output.dt.
  Recorder(model::CollisionModel& model, const Scene& sc, bool progress, bool forces = true, double sample_dt = 0);

  void sample(double t, std::span<const double> y, bool at_event) override;
  void quadratures(std::span<const double> q) override;
  /// After each accepted step: ends the run (throws Interrupted) when this thread's work was asked to stop.
  void stepped(long steps) override {
    steps_ = steps;
    stop_.throw_if_requested();
  }
  /// With forces and the history force: a row at the end of every accepted step while the gap is below 3 δ_SS
  /// (contact_rows), where the history force peaks faster than output.dt resolves. Otherwise nothing.
  void step_end(double t, std::span<const double> y) override;
  /// Clears the progress line, if one was shown.
  void finish_progress();
  /// Shows `text` as the progress line (the same terminal and pacing rules): work before t = 0, such as a coupled
  /// run's flow start-up.
  void show_status(const std::string& text);

  const std::vector<std::string>& columns() const { return columns_; }
  std::vector<std::vector<double>>& rows() { return rows_; }
  /// The measures' samples: every sample of the run (each row among them).
  const Track& track() const { return track_; }
  /// The rows at the solver's steps near contact (step_end), in time order; kept apart from rows().
  std::vector<std::vector<double>>& contact_rows() { return contact_rows_; }
  double min_gap() const { return min_gap_; }          // m, over the samples
  bool forces() const { return forces_; }
  double max_contact_force() const { return max_force_; }  // N, sphere 1 (forces() only)
  double max_history_force() const { return max_history_; }  // N, any sphere, over rows() and contact_rows() (forces() only)

 private:
  void show_progress(double t);
  void add_to_track(double t, const model::Evaluation& ev);
  /// The energy budget's samples (Track::work, ke_spheres, ke_added) at a sample of the track.
  void add_energies(const model::Evaluation& ev);
  /// The row of columns() at (t, ev); updates the peak history force.
  std::vector<double> make_row(double t, const model::Evaluation& ev, bool at_event);

  model::CollisionModel& model_;
  const Scene& sc_;
  std::vector<std::string> columns_;
  std::optional<std::size_t> contact_slot_, history_slot_;  // the slots of the peaks kept (contact, history force)
  std::vector<std::vector<double>> rows_, contact_rows_;
  Track track_;
  std::array<double, model::kForceKinds> work_{};  // the quadratures of the sample being taken, J
  double sample_dt_, next_row_;  // s
  long k_row_ = 1;
  double min_gap_, max_force_ = 0, max_history_ = 0;
  long steps_ = 0;
  bool forces_ = true, progress_ = false, shown_ = false;
  WallClock::time_point start_ = WallClock::now(), last_ = start_;
  WallClock::time_point t0_ = start_;  // when t = 0 was sampled: the projection counts from there
  ProgressEstimate estimate_;
  const StopToken stop_ = this_thread_work().stop;
  ProgressMeter* const meter_ = this_thread_work().meter;  // simulated s of t_end, at every sample
  bool sampled_ = false;
  const bool contact_rows_on_;  // step_end keeps rows (forces, a contact and the history force)
  const double contact_zone_;   // m: 3 δ_SS, the gap below which step_end keeps rows
};

}  // namespace imcol::run
