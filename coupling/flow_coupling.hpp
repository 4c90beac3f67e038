// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The coupling loop (MODEL.md §2, (6.10), §5): the flow kernel supplies f_SIM to the collision model each flow step.
//
// Partitioned, one pass per flow step Δt = t_{n+1} − t_n:
//   1. predict the spheres at t_{n+1} from the ODE state at t_n: z + uΔt + ½aΔt², u + aΔt;
//   2. step the flow kernel to t_{n+1} with the predicted spheres, in a frame that follows the pair's midpoint
//      (the grid never loses the spheres); F_lab = F_frame + ρ V a_frame;
//   3. remove the model's added-mass estimate: f_rest = F_lab + M_A a_flow, a_flow the kernel's velocity change
//      over the step / Δt, M_A the added-mass matrix the model keeps implicit (so light spheres stay stable: the
//      fluid's inertia never enters explicitly, only the difference between the kernel's and the model's);
//   4. CVODE/IDA integrate particle and memory states over [t_n, t_{n+1}] with f_rest linear in t between its
//      values at t_n and t_{n+1} (`flow.force_in_step = "linear"`, the default: averaging two steps damps the
//      alternating mode that the remaining explicit part of the fluid's inertia drives; measured order in Δt ≈ 0.8)
//      or held at the kernel's step value ("held": the IB force is the step's impulse over Δt, order ≈ 1.3, but
//      unstable for light spheres); contact events inside the step are handled by the integrator as in the
//      reduced model; a held force jumps at t_n, so the integrator is re-initialised there.
// After 2 the kernel's force, after 4 the spheres' speeds and energy are checked (divergence_watch.hpp); the step
// Δt comes from coupling/step_rule.hpp.
// The flow starts impulsively (one prescribed step before t = 0) or developed (initial velocities prescribed over a
// stated distance or time before t = 0). Near contact the gap seen by the kernel is kept at flow.min_gap_cells·h
// or more (its rings would overlap): there H ≈ 1 and f_SIM's weight is small (documented in docs/coupling.md).
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/collision_model.hpp"
#include "core/timing.hpp"
#include "core/work_scope.hpp"
#include "core/scene.hpp"
#include "coupling/adaptive_step.hpp"
#include "coupling/flow_run_stats.hpp"
#include "coupling/step_rule.hpp"
#include "flow/field_series.hpp"
#include "flow/solver.hpp"
#include "integrators/integrator.hpp"

namespace imcol::coupling {

class DivergenceWatch;

/// The reduced-order model's run of the same scene (run/simulate.cpp): when it ended, and the spheres' path, along
/// which the cost estimate and the automatic preconditioner bins count the adaptive flow steps.
struct ExpectedRun {
  double end = 0;                           // s; 0: unknown (t_end)
  std::optional<double> t_contact, t_separation;  // s, the model's first δ_SS crossings
  std::vector<double> t;                    // s
  std::vector<std::array<double, 2>> z, u;  // the spheres' centres (m) and velocities (m/s) at t
};

class FlowCoupling {
 public:
  FlowCoupling(model::CollisionModel& model, const Scene& scene);
  ~FlowCoupling();
  /// Runs the coupled integration to the model's stop time; returns the ODE statistics. Throws SolverError
  /// (the kernel diverged or GMRES failed, the ODE failed) naming the time and the quantity.
  SolverStats run(const IntegratorSettings& st, Observer& observer);
  const FlowRunStats& stats() const { return stats_; }
  /// Receives a progress text during the start-up (before t = 0: the flow developing, the force system's blocks).
  void set_progress(std::function<void(const std::string&)> f) { progress_ = std::move(f); }
  /// Where the flow-field files go as they are made (flow/field_series.hpp): names relative to the output folder.
  /// Without a sink (sweeps, comparisons) no flow fields are computed, whatever flow.fields says.
  void set_file_sink(flow::FileSink sink) { sink_ = std::move(sink); }
  /// How the run will likely go (the reduced-order model's run): the cost estimate and the automatic preconditioner
  /// bins count the steps to its end, with flow.adaptive_step along its path.
  void set_expected_run(ExpectedRun r) { expected_ = std::move(r); }

 private:
  struct Predicted {
    std::array<double, 2> z{}, u{};
    double gap = 0;
  };
  Predicted predict(double t, std::span<const double> y, double dt) const;
  double gap_of(const std::array<double, 2>& z) const;  // surface gap to the target sphere or the wall; ∞ if none
  std::vector<flow::SphereState> frame_spheres(const Predicted& p, double frame_z, double frame_u);
  std::array<double, 2> step_kernel(const Predicted& p, double dt);
  double next_step(std::span<const double> y);  // the coming flow step (adaptive), set in the kernel
  /// The start-up before t = 0 (impulsive or developed): the grid is built and the flow developed with the spheres
  /// on their initial paths.
  void start_up();
  struct StartUp {      // the start-up's plan
    double h = 0;       // finest spacing, m
    double dt = 0;      // flow step, s
    double u_mid = 0;   // the frame's velocity (the spheres' midpoint), m/s
    long n_pre = 1;     // prescribed flow steps before t = 0
    double t_pre = 0;   // their duration, s
  };
  StartUp plan_start_up();  // the step and the start-up's length (InputError beyond 1e8 steps)
  /// Cells of the finest level along an extent (m), a multiple of `multiple`; InputError beyond 1e6.
  int finest_cells(const StartUp& su, double extent, int multiple) const;
  flow::Settings grid_settings(const StartUp& su);  // the kernel's grid; places the frame
  std::array<double, 2> start_up_travel(const StartUp& su) const;  // each sphere's travel relative to the grid, m
  int preconditioner_bins(const flow::Settings& s, const StartUp& su) const;  // flow.preconditioner_bins, or chosen
  double run_end() const;                      // s: the expected end, at most t_end
  /// Coupled flow steps to run_end(): of dt, or with the adaptive step the rule's along the expected path.
  double flow_steps_to_end(double dt) const;
  /// Flow-field snapshots a file sink will take (maybe_snapshot, finish_series) along the expected path.
  double snapshots_to_end() const;
  Predicted prescribed(double t) const;  // the spheres on their initial paths at t < 0
  std::array<double, 2> develop_flow(const StartUp& su, const flow::Settings& s);  // builds the kernel; its last f
  void reset_step_stats();
  /// Estimates the run's cost (stats_.est_*) and refuses (InputError) a grid beyond half the memory or a run beyond
  /// flow.max_wall_hours, before allocating. `travel`: each sphere's travel relative to the grid over the start-up, m.
  void check_cost(const flow::Settings& s, double dt, long n_pre, const std::array<double, 2>& travel);
  void report_start_up(long step, long n_pre, const std::string& doing);
  void maybe_snapshot(double t, double gap);
  void take_snapshot(const std::string& name, const std::string& label);
  void take_regular();  // the flow.fields_every snapshot named by the step
  void start_series();   // the field series when flow.fields and a sink, its first regular snapshot
  void finish_series();  // the end's snapshot
  /// integ.advance(t1) timed; a failure after the flow fed the spheres energy is named as the coupling's.
  double advance(Integrator& integ, const DivergenceWatch& watch, double t1);
  std::array<double, 2> acting(const std::array<double, 2>& f_rest, std::span<const double> y) const;  // (1 − H) f_rest
  /// The kernel's fields seen from the lab, times from the collision's t = 0, with the spheres where the trajectory
  /// has them (note_trajectory: the ODE state at the end of the flow step, the stop time at the run's end).
  flow::SnapshotFrame lab_frame() const;
  void note_trajectory(std::span<const double> y);  // the model's sphere positions and velocities for the snapshots

  model::CollisionModel& model_;
  const Scene& sc_;
  std::size_t n_ = 1;
  std::array<double, 2> radius_{}, volume_{};
  double D_ = 0, rho_ = 0, u_ref_ = 0;
  std::unique_ptr<flow::Solver> kernel_;
  double frame_z_ = 0, frame_u_ = 0;         // frame origin and velocity in the lab (m, m/s)
  double t_pre_ = 0;                         // start-up time before t = 0, s
  std::array<double, 2> kernel_u_{};         // lab velocities the kernel last imposed (m/s)
  std::array<double, 2> f_rest_{};           // f_rest at the last flow time
  std::array<double, 2> start_force_{};      // f_rest at the end of the start-up
  FlowStep step_;                            // the flow step and how it was chosen (coupling/step_rule.hpp)
  std::optional<AdaptiveStep> adapt_;        // the step as the run goes on
  double u_fluid_ = 0;                       // the fluid's largest speed after the last flow step, m/s
  bool have_f_rest_ = false;
  FlowRunStats stats_;
  flow::FileSink sink_;
  std::optional<flow::FieldSeries> series_;  // with flow.fields and a sink
  std::array<double, 2> traj_z_{}, traj_u_{};  // the spheres as the model has them at the last step's end (lab)
  double next_every_ = 0;                    // next regular snapshot (flow.fields_every), s
  std::function<void(const std::string&)> progress_;
  StopToken stop_ = this_thread_work().stop;  // checked before every flow step and force-system column
  WallClock::time_point start_up_began_{};
  double est_before_t0_s_ = 0;  // estimated start-up and its blocks, s
  ExpectedRun expected_;        // the reduced-order model's run
  bool snap_gap_ = false, snap_contact_ = false, snap_after_ = false;
};

}  // namespace imcol::coupling
