// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a flow run will cost, estimated from its grid before anything is allocated (measured constants:
// docs/flow-kernel.md "cost"). Memory ~100 bytes per vertex and level plus the force system's dense matrices (Q of
// the body points, its LU, and up to preconditioner_bins cached blocks per moving sphere). Time, in units of one
// application of the force operator Q (a multi-level solve pair, 2 × levels fast solves; per vertex and level its
// cost grows with the grid as the arrays leave the caches, flow/cost.cpp):
//   step with fixed bodies (LU):           explicit part + 2 Q       (predictor and final pass)
//   step with moving bodies (GMRES, k it.): explicit part + (3 + k) Q (predictor, warm start, k iterations, final)
//   a block of the force system of n unknowns (its columns by Q, then LU): n Q + n³ LU flops.
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
  double seconds_explicit = 0;  // a step's explicit part (advection, viscous right-hand side), s
  double seconds_per_step = 0;  // s, a step with fixed bodies, or with moving ones at a typical GMRES count
};

/// `diameters`: the spheres' (m); `moving`: bodies move relative to the grid.
CostEstimate estimate_cost(const Settings& s, std::span<const double> diameters, bool moving);

/// Ring points of a sphere of diameter d (m) on the finest level.
double ring_points(const Settings& s, double d);

/// A step's wall time, s: fixed bodies (LU), or moving ones with `iterations` GMRES iterations.
double step_seconds(const CostEstimate& c, bool moving, double iterations);

/// Building one block of the force system with n unknowns (n applications of Q, then its LU), s.
double block_seconds(const CostEstimate& c, double n);

/// GMRES iterations per step assumed for moving bodies (measured 5–21 in coupled runs), during the coupled steps
/// and the prescribed start-up alike.
inline constexpr double kTypicalGmresIterations = 10;
inline constexpr double kStartUpGmresIterations = 10;

/// This machine's physical memory, B (0 if unknown).
double physical_memory_bytes();

/// Empty if the estimate fits in half of this machine's memory; otherwise why not ("needs about … GB (…
/// vertices, … body points), more than half of this machine's … GB"), for the caller's error message.
std::string memory_refusal(const CostEstimate& c);

}  // namespace imcol::flow
