// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The statistics of a coupled flow run (coupling/flow_coupling.hpp): steps, grid, wall times (s), the Krylov solves,
// the stability measures and the cost estimated before the grid was allocated.
#include <cstddef>

namespace imcol::coupling {

struct FlowRunStats {
  long steps = 0;             // coupled flow steps
  long pre_steps = 0;         // prescribed steps before t = 0 (start-up)
  double dt = 0;              // flow step, s (the first, with flow.adaptive_step)
  double dt_min = 0, dt_max = 0;  // the shortest and longest coupled flow steps, s
  long step_changes = 0;      // times the adaptive step changed (coupling/adaptive_step.hpp)
  double h = 0;               // finest spacing, m
  int nr = 0, nz = 0, levels = 0, cells_per_diameter = 0;
  double flow_seconds = 0, ode_seconds = 0, pre_seconds = 0;  // wall time in the kernel, in CVODE/IDA, in the start-up
  long krylov_iterations = 0;
  int max_krylov_iterations = 0;
  // Over the whole run, start-up included: applications of the force operator Q (GMRES iterations, warm starts,
  // preconditioner block columns and probes, LU columns) and the preconditioner blocks built.
  long q_applications = 0, preconditioner_blocks = 0;
  long pre_q_applications = 0;     // of q_applications, those of the start-up
  double max_krylov_residual = 0, max_slip = 0;  // m/s
  double cfl = 0;                  // Courant number of U_ref that gave dt (0: flow.dt given)
  double max_courant = 0;          // the fluid's largest advective Courant number (flow/solver.hpp max_courant)
  double max_energy_ratio = 0;     // largest kinetic energy / available energy (coupling/divergence_watch.hpp)
  long min_gap_clamped_steps = 0;  // steps where the kernel's gap was held at min_gap_cells·h
  double frame_travel = 0;         // m, how far the grid moved with the spheres
  std::size_t bytes = 0;
  // Estimated before the grid was allocated (coupling/run_cost.hpp), s and B: the start-up's steps, the force
  // system's blocks, the coupled steps to the expected end, the flow-field snapshots, and the solver's memory.
  double est_start_up_s = 0, est_blocks_s = 0, est_steps_s = 0, est_fields_s = 0, est_bytes = 0;
  double est_q_applications = 0, est_steps = 0, est_field_snapshots = 0;  // the counts behind those times
  double est_total_s() const { return est_start_up_s + est_blocks_s + est_steps_s + est_fields_s; }
  int field_snapshots = 0;         // flow-field snapshots taken
  double fields_seconds = 0;       // wall time computing and writing them, s
  double cpu_seconds = 0;          // CPU time of the whole coupled run (start-up, steps, fields), s
};

}  // namespace imcol::coupling
