// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What `imcol calibrate` minimises, for one set of parameter values:
//  * trajectory: the mean square of z_sim(t_k - tau) - z_meas(t_k) over the window's samples and the measured
//    columns (m^2), minimised also over the time offset tau in [-tau_max, tau_max] (the measurement's clock minus
//    the simulation's); the window is [t_c + before, t_c + after] around the measured contact t_c, the time of
//    the smallest measured gap (to the wall or between the spheres) given the scene's radii;
//  * e table: the mean square of e_sim - e_meas over the rows (each row one run, measured as imcol sweep measures a
//    point, solver.t_end doubled at most twice while too short; a run with no rebound has e = 0 in its summary; a run
//    without e, such as one with no collision by t_end, makes the evaluation fail with its reason).
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "calibrate/measurement.hpp"
#include "core/scene.hpp"
#include "run/simulate.hpp"

namespace imcol::calib {

struct TrajectoryWindow {
  double t_contact = 0;      // s, measured contact (smallest measured gap)
  double before = 0, after = 0;  // s, relative to t_contact (before < 0 < after)
  double tau_max = 0;        // s, bound on |tau|
};

/// The default window for a trajectory on `scene`: one diameter of travel at the approach speed before the measured
/// contact and two after, clipped to the record; tau_max half of that travel time. `before`/`after`/`tau_max`
/// given (the options --window A:B, --offset-max T) replace the defaults. Fewer than kMinTrajectoryRows samples in the
/// window throws InputError naming the option or the file; a z2 column on a one-sphere scene, naming the header line.
TrajectoryWindow trajectory_window(const MeasuredTrajectory& m, const Scene& scene, std::optional<double> before,
                                   std::optional<double> after, std::optional<double> tau_max);

/// The window's samples: the rows [first, second) of `m`, those with t in [t_contact + before, t_contact + after].
std::pair<std::size_t, std::size_t> window_rows(const MeasuredTrajectory& m, const TrajectoryWindow& w);

/// One objective evaluation's outcome.
struct Evaluation {
  bool ok = false;
  double objective = 0;        // mean square residual (m^2 or e^2); +inf when !ok
  double rms = 0;              // sqrt(objective), in m or e
  std::optional<double> tau;   // s, the fitted offset (trajectory)
  std::size_t residuals = 0;   // n, the residuals the mean is taken over (window samples x columns, or table rows)
  std::vector<double> e_sim;   // per table row (table); NaN where a run failed
  std::string message;         // why it failed (solver failure, input error of a row's scene)
  double wall_s = 0;
};

/// The trajectory objective of a finished run (its columns t, z1, z2). Samples whose t_k - tau lies before the run's
/// first row take the first rows' straight line (the approach at constant speed); past its last row, the last value
/// (a run that ended at rest).
Evaluation trajectory_objective(const MeasuredTrajectory& m, const TrajectoryWindow& w, const RunResult& run);

/// The scene evaluate_trajectory runs: the scene file with `overrides`, its t_end covering the window's end at the
/// largest offset, every bounce followed. Throws InputError.
Scene trajectory_scene(const TrajectoryWindow& w, const std::string& scene_path, const std::vector<Override>& overrides);

/// Runs `scene` with `values` set (its t_end long enough to cover the window and the offsets) and scores it.
/// Never throws for a failed run: ok is false then.
Evaluation evaluate_trajectory(const MeasuredTrajectory& m, const TrajectoryWindow& w, const std::string& scene_path,
                               const std::vector<Override>& overrides);
/// Every row's scene of an e table (`overrides`, then the row's keys at the row's values) is a valid scene: else
/// InputError(FILE:LINE of the row, the key the scene reader names, its problem). The one check of a table's keys.
void check_table_keys(const MeasuredTable& m, const std::string& scene_path, const std::vector<Override>& overrides);

/// Runs each table row's scene (`overrides`, then the row's keys) and scores them. Never throws for a failed run.
Evaluation evaluate_table(const MeasuredTable& m, const std::string& scene_path, const std::vector<Override>& overrides);

}  // namespace imcol::calib
