// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a flow scene's run (run/flow_run.hpp) found: the drag and its comparison with the standard curve, the forces
// compared with the analytic references (run/flow_references.hpp), the grid, the steps and the force solver's
// statistics; SI units. run/flow_run_json.hpp writes it as summary.json.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace imcol {

/// C_D of sphere 1 at the last step against the steady standard curve, which is a reference only once the drag has
/// settled (run/flow_run.cpp says when).
struct FlowDragComparison {
  double coefficient = 0;                    // C_D at the last step (NaN without a step)
  double change_last_tenth_percent = 0;      // |ΔC_D| / C_D over the last tenth of the run, %
  bool settled = false;
  double left_to_settle_percent = 0;         // extrapolated, t^(-1/2) tail, %
  double distance_passed_D = 0;              // t U / D
  std::optional<double> standard;            // the standard curve's C_D; settled, one sphere
  std::optional<double> error_percent;       // against it
  double stokes_drag_ratio = 0;              // F / 6πμaU
};

/// An impulsive start at Re <= 1 against Stokes + Basset, F = 6πμaU (1 + a / sqrt(πνt)), over 0.8 <= νt/a² <= 4.
struct FlowImpulsiveStart {
  double window_t0 = 0, window_t1 = 0;  // s
  double max_rel_error = 0;
};

/// One sphere: its wake and how soon C_D came within 3 % of the standard curve (settled runs only).
struct FlowOneSphere {
  std::optional<double> wake_length_D;  // steady runs in a stream
  std::optional<double> time_to_3pct_s, wall_time_to_3pct_s;
  std::optional<FlowImpulsiveStart> impulsive_start;
};

/// The smallest gap the run reached (between neighbours, or to the wall).
struct FlowGapSeen {
  double min_gap_D = 0;
  bool resolved = false;  // at least 3 cells: the delta kernels did not overlap
};

/// f_SIM against f_THR as the gap first fell to a report gap (1, 0.5, 0.25, 0.1, 0.05 D): for two spheres the
/// reduced-order pair forces, for a sphere and a wall Brenner's (1961) force and the wall's.
struct FlowGapForces {
  double gap_D = 0, gap_cells = 0;
  bool resolved = false;
  double F1 = 0, F_THR1 = 0;              // N
  std::optional<double> F2, F_THR2;       // two spheres
  std::optional<double> F_wall;           // a sphere and a wall
};

struct FlowWall {
  double position = 0;   // m
  double force_N = 0;    // at the last step
  bool brenner = false;  // f_THR is Brenner's (one sphere)
};

/// One sphere oscillating in fluid at rest against the unsteady Stokes force, over the last period.
struct FlowOscillating {
  double delta_over_a = 0;  // Stokes layer thickness / radius
  double max_error_rel_amplitude = 0;
};

struct FlowGridBox {
  double r_max = 0, z_min = 0, z_max = 0;  // m
};

struct FlowGrid {
  int cells_per_diameter = 0;
  double h = 0;  // finest spacing, m
  int levels = 0, nr = 0, nz = 0;
  FlowGridBox finest, coarsest;
  std::size_t body_points = 0;
};

struct FlowForceSolver {
  double krylov_tol = 0;
  double krylov_iterations_mean = 0;
  int krylov_iterations_max = 0;
  double max_slip = 0;  // m/s
};

struct FlowRunResult {
  std::string forces_csv;  // the force history (forces.csv)
  std::string scene, name;
  double Re = 0;
  FlowDragComparison drag;
  std::optional<FlowOneSphere> one_sphere;             // one sphere
  std::vector<double> forces_N;                        // each sphere's at the last step
  std::optional<FlowGapSeen> gap;                      // several spheres, or one and a wall
  std::optional<std::vector<FlowGapForces>> gap_forces;  // two spheres, or one and a wall
  std::optional<FlowWall> wall;
  std::optional<FlowOscillating> oscillating;
  FlowGrid grid;
  double dt = 0, theta = 0;  // s, time-stepping weight
  long steps = 0;
  double t_end = 0;          // reached, s
  double wall_time_s = 0, ms_per_step = 0;
  std::size_t memory_bytes = 0;
  FlowForceSolver force_solver;
};

}  // namespace imcol
