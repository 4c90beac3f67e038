// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a coupled run will cost, before the flow grid is allocated (flow/cost.hpp gives the kernel's unit costs):
//   start-up    n_pre prescribed steps before t = 0 (flow.developed_distance or developed_time over Δt); with moving
//               spheres each takes a_0 GMRES iterations (a_0 = 5 per moving sphere, with or without the wall: a
//               prescribed constant speed revisits the sub-cell offsets whose blocks were built, so the blocks are
//               exact; at flow.krylov_tol 1e-8, scaled to the run's by krylov_tolerance_factor);
//   force system blocks: with the bodies still relative to the grid one LU of the whole force system (2 × all ring
//               points); with moving spheres one preconditioner block (2 × the sphere's ring points) per sub-cell
//               offset bin the sphere visits (flow.preconditioner_bins; a sphere that travels d relative to the grid
//               visits min(bins, 1 + bins d/h) of them), the first of each sphere diameter column by column and the
//               later ones probed (flow/cost.hpp later_block_applications), plus the wall's own block once;
//   steps       the coupled steps to the expected end, each with a_0 + bin_iterations(bins, tol) GMRES iterations
//               (coupling/preconditioner_bins.hpp) when the spheres move relative to the grid, plus the ODE's share;
//   fields      the flow-field snapshots a file sink takes along the expected path (FlowCoupling::snapshots_to_end).
// Each part is also counted (applications of Q, steps, snapshots: flow.estimate in summary.json), so that the counts
// can be checked against the run's own apart from the machine (bench/coupled_estimate.py --check-q).
// The expected end is the reduced-order model's (at rest, separated and measured, or t_end): the coupled run's own
// differs by its flow force; t_end is the bound.
#include <vector>

#include "flow/cost.hpp"

namespace imcol::coupling {

struct CoupledCostInput {
  flow::Settings settings;
  std::vector<double> diameters;       // m
  long start_up_steps = 0;
  double steps = 0;                    // coupled steps to the expected end
  double snapshots = 0;                // flow-field snapshots
  std::vector<double> start_up_travel; // each sphere's travel relative to the grid over the start-up, m
  std::vector<bool> moves_after;       // each sphere moves relative to the grid after t = 0
};

struct CoupledCost {
  flow::CostEstimate grid;
  double start_up_s = 0;        // the start-up's steps
  double blocks_s = 0;          // force system LU and preconditioner blocks (start-up and run)
  double steps_s = 0;           // the coupled steps to the expected end
  double fields_s = 0;          // the flow-field snapshots
  double start_up_blocks_s = 0; // the part of blocks_s built during the start-up
  double q_applications = 0;    // applications of Q over the whole run (GMRES, warm starts' residuals, blocks)
  double total_s() const { return start_up_s + blocks_s + steps_s + fields_s; }
  double before_t0_s() const { return start_up_s + start_up_blocks_s; }
};

CoupledCost coupled_cost(const CoupledCostInput& in);

/// ODE integration (CVODE/IDA, events, recording) per coupled flow step, s (measured 7–140 µs, most 20–60 µs).
inline constexpr double kOdeSecondsPerStep = 2.2e-5;

/// GMRES iterations a step with each moving sphere's block at its exact sub-cell offset, per moving sphere
/// (measured at flow.krylov_tol 1e-8: ~10 for a pair, 4–5 for a sphere and the wall).
inline constexpr double kGmresIterationsPerBody = 5;

}  // namespace imcol::coupling
