// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a flow run will cost, estimated from its grid before anything is allocated (docs/performance.md §7). Memory
// ~100 bytes per vertex and level plus the force system's dense matrices (Q of the body points, its LU, and up to
// preconditioner_bins cached blocks per moving sphere). Time, from the kernel's passes over the V vertices of all
// levels (flow/solver.hpp), each a fixed cost per vertex measured on this kernel:
//   a step's own work (explicit part, the predictor η* and ψ*, the end-of-step pass in full): kStepPerVertex V, or
//   kMovingStepPerVertex V with bodies moving relative to the grid (their point rows rebuilt every step);
//   one application of the force operator Q (the partial passes of a force source): kQPerVertex V;
//   step with fixed bodies (LU): the step's own work (the LU's solve is n², negligible);
//   step with moving bodies (GMRES, k iterations): the step's own work + (1 + k) Q (the warm start's residual);
//   a block of the force system of n unknowns (its columns by Q, then LU): n Q + kLuPerCube n³; a sphere's later
//   preconditioner blocks (probed from the first of its radius): 2 min(points, block_probe_stride) Q + kLuPerCube n³;
//   a flow-field snapshot (the fields, CSV and VTK written): kFieldPerVertex V.
#include <span>
#include <string>

#include "flow/solver.hpp"

namespace imcol::flow {

struct CostEstimate {
  double vertices = 0;          // all levels
  double body_points = 0;       // rings of the spheres and the wall
  double sphere_points = 0;     // rings of the largest sphere
  double wall_points = 0;       // rings of the wall (all levels)
  double bytes = 0;             // peak memory of the solver, B
  double seconds_per_q = 0;     // one application of Q, s
  double seconds_explicit = 0;  // a step's own work (explicit part, predictor, end-of-step pass), s
  double seconds_per_step = 0;  // s, a step with fixed bodies, or with moving ones at kTypicalGmresIterations
  double seconds_per_field = 0; // one flow-field snapshot, s
};

/// `diameters`: the spheres' (m); `moving`: bodies move relative to the grid.
CostEstimate estimate_cost(const Settings& s, std::span<const double> diameters, bool moving);

/// Ring points of a sphere of diameter d (m) on the finest level.
double ring_points(const Settings& s, double d);

/// A step's applications of Q: none with fixed bodies (LU), 1 + `iterations` with moving ones (the warm start's residual).
double step_applications(bool moving, double iterations);
/// A step's time, s: fixed bodies (LU), or moving ones with `iterations` GMRES iterations.
double step_seconds(const CostEstimate& c, bool moving, double iterations);

/// Building one block of the force system with n unknowns (n applications of Q, then its LU), s.
double block_seconds(const CostEstimate& c, double n);
/// The same block built from `applications` applications of Q (a probed block: later_block_applications), s.
double block_seconds(const CostEstimate& c, double n, double applications);

/// Applications of Q that a sphere's later preconditioner block takes (one of its radius already built): 2 ×
/// min(points, block_probe_stride), or 2 × points with block_probe_stride = 0 (flow/solver.hpp).
double later_block_applications(const Settings& s, double points);

/// GMRES iterations per step assumed for moving bodies where nothing better is known (`imcol flow`; coupled runs:
/// coupling/run_cost.hpp); measured 5–22.
inline constexpr double kTypicalGmresIterations = 10;

/// This machine's physical memory, B (0 if unknown).
double physical_memory_bytes();

/// Empty if the estimate fits in half of this machine's memory; otherwise why not ("needs about … GB (…
/// vertices, … body points), more than half of this machine's … GB"), for the caller's error message.
std::string memory_refusal(const CostEstimate& c);

}  // namespace imcol::flow
