// SPDX-License-Identifier: BSD-3-Clause
#include "coupling/run_cost.hpp"

#include <algorithm>
#include <cmath>

#include "coupling/preconditioner_bins.hpp"

namespace imcol::coupling {

CoupledCost coupled_cost(const CoupledCostInput& in) {
  const flow::Settings& s = in.settings;
  CoupledCost c;
  bool start_moving = false, run_moving = false;
  for (double d : in.start_up_travel) start_moving = start_moving || d > 0;
  for (bool m : in.moves_after) run_moving = run_moving || m;
  c.grid = flow::estimate_cost(s, in.diameters, start_moving || run_moving);
  const double bins = std::max(1, s.preconditioner_bins);
  double built_before = 0, built_after = 0, q_blocks = 0;
  // `count` blocks of sphere m: the first of its diameter column by column, the later ones probed.
  std::vector<double> built_diameters;
  auto block = [&](double n, double applications, double count = 1) {
    q_blocks += count * applications;
    return count * flow::block_seconds(c.grid, n, applications);
  };
  auto sphere_blocks = [&](std::size_t m, double count) {
    const double d = in.diameters[m], points = flow::ring_points(s, d), n = 2 * points;
    double t = 0;
    if (count > 0 && std::find(built_diameters.begin(), built_diameters.end(), d) == built_diameters.end()) {
      built_diameters.push_back(d);
      t += block(n, n);
      count -= 1;
    }
    return t + block(n, flow::later_block_applications(s, points), std::max(0.0, count));
  };
  bool wall_block = false;
  auto wall = [&](double& into) {
    if (c.grid.wall_points > 0 && !wall_block) into += block(2 * c.grid.wall_points, 2 * c.grid.wall_points);
    wall_block = true;
  };
  // Start-up: one LU of the whole system while the bodies are still, else the blocks of the bins visited.
  if (!start_moving) {
    built_before += block(2 * c.grid.body_points, 2 * c.grid.body_points);
  } else {
    for (std::size_t m = 0; m < in.diameters.size(); ++m) {
      if (!(in.start_up_travel[m] > 0)) continue;
      const double visited = std::min(bins, 1 + std::floor(bins * in.start_up_travel[m] / s.h));
      built_before += sphere_blocks(m, visited);
    }
    wall(built_before);
  }
  // The coupled steps: a sphere that moves relative to the grid visits every bin (the rest of them).
  if (run_moving) {
    for (std::size_t m = 0; m < in.diameters.size(); ++m) {
      if (!in.moves_after[m]) continue;
      const double before = in.start_up_travel[m] > 0 ? std::min(bins, 1 + std::floor(bins * in.start_up_travel[m] / s.h)) : 0;
      built_after += sphere_blocks(m, bins - before);
    }
    wall(built_after);
  }
  // GMRES iterations: a_0 per moving sphere, more between the bins' offsets.
  double moving = 0;
  for (std::size_t m = 0; m < in.diameters.size(); ++m) moving += (in.start_up_travel[m] > 0 || in.moves_after[m]) ? 1 : 0;
  const double a0 = kGmresIterationsPerBody * krylov_tolerance_factor(s.krylov_tol) * std::max(1.0, moving);
  const double a_run = a0 + bin_iterations(s.preconditioner_bins, s.krylov_tol);
  c.start_up_s = double(in.start_up_steps) * flow::step_seconds(c.grid, start_moving, a0);
  c.steps_s = in.steps * (flow::step_seconds(c.grid, run_moving, a_run) + kOdeSecondsPerStep);
  c.q_applications = q_blocks + (start_moving ? double(in.start_up_steps) * (1 + a0) : 0.0) + (run_moving ? in.steps * (1 + a_run) : 0.0);
  c.fields_s = in.snapshots * c.grid.seconds_per_field;
  c.start_up_blocks_s = built_before;
  c.blocks_s = built_before + built_after;
  return c;
}

}  // namespace imcol::coupling
