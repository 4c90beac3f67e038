// SPDX-License-Identifier: BSD-3-Clause
#include "coupling/run_cost.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "coupling/preconditioner_bins.hpp"

namespace imcol::coupling {

namespace {

/// The sub-cell offset bins a sphere that travels `travel` relative to the grid visits: min(bins, 1 + bins travel/h).
double visited_bins(double bins, double travel, double h) { return travel > 0 ? std::min(bins, 1 + std::floor(bins * travel / h)) : 0.0; }

/// The force system's blocks as they are built, their time and their applications of Q.
struct BlockLedger {
  const flow::Settings& s;
  const flow::CostEstimate& grid;
  std::vector<double> built_diameters;  // a sphere's first block is built column by column once per diameter
  bool wall_built = false;
  double q_applications = 0;

  double block(double n, double applications, double count = 1) {
    q_applications += count * applications;
    return count * flow::block_seconds(grid, n, applications);
  }
  /// `count` blocks of a sphere of diameter d: the first of its diameter column by column, the later ones probed.
  double sphere(double d, double count) {
    const double points = flow::ring_points(s, d), n = 2 * points;
    double t = 0;
    if (count > 0 && std::find(built_diameters.begin(), built_diameters.end(), d) == built_diameters.end()) {
      built_diameters.push_back(d);
      t += block(n, n);
      count -= 1;
    }
    return t + block(n, flow::later_block_applications(s, points), std::max(0.0, count));
  }
  /// The wall's own block, once.
  double wall() {
    const double t = grid.wall_points > 0 && !wall_built ? block(2 * grid.wall_points, 2 * grid.wall_points) : 0.0;
    wall_built = true;
    return t;
  }
};

}  // namespace

CoupledCost coupled_cost(const CoupledCostInput& in) {
  const flow::Settings& s = in.settings;
  CoupledCost c;
  bool start_moving = false, run_moving = false;
  for (double d : in.start_up_travel) start_moving = start_moving || d > 0;
  for (bool m : in.moves_after) run_moving = run_moving || m;
  c.grid = flow::estimate_cost(s, in.diameters, start_moving || run_moving);
  const double bins = std::max(1, s.preconditioner_bins);
  BlockLedger blocks{s, c.grid, {}};
  double built_before = 0, built_after = 0;
  // Start-up: one LU of the whole system while the bodies are still, else the blocks of the bins visited.
  if (!start_moving) {
    built_before += blocks.block(2 * c.grid.body_points, 2 * c.grid.body_points);
  } else {
    for (std::size_t m = 0; m < in.diameters.size(); ++m)
      built_before += blocks.sphere(in.diameters[m], visited_bins(bins, in.start_up_travel[m], s.h));
    built_before += blocks.wall();
  }
  // The coupled steps: a sphere that moves relative to the grid visits every bin (the rest of them).
  if (run_moving) {
    for (std::size_t m = 0; m < in.diameters.size(); ++m)
      if (in.moves_after[m]) built_after += blocks.sphere(in.diameters[m], bins - visited_bins(bins, in.start_up_travel[m], s.h));
    built_after += blocks.wall();
  }
  // GMRES iterations: a_0 per moving sphere, more between the bins' offsets.
  double moving = 0;
  for (std::size_t m = 0; m < in.diameters.size(); ++m) moving += (in.start_up_travel[m] > 0 || in.moves_after[m]) ? 1 : 0;
  const double a0 = kGmresIterationsPerBody * krylov_tolerance_factor(s.krylov_tol) * std::max(1.0, moving);
  const double a_run = a0 + bin_iterations(s.preconditioner_bins, s.krylov_tol);
  const double pre = static_cast<double>(in.start_up_steps);
  c.start_up_s = pre * flow::step_seconds(c.grid, start_moving, a0);
  c.steps_s = in.steps * (flow::step_seconds(c.grid, run_moving, a_run) + kOdeSecondsPerStep);
  c.q_applications =
      blocks.q_applications + pre * flow::step_applications(start_moving, a0) + in.steps * flow::step_applications(run_moving, a_run);
  c.fields_s = in.snapshots * c.grid.seconds_per_field;
  c.start_up_blocks_s = built_before;
  c.blocks_s = built_before + built_after;
  return c;
}

}  // namespace imcol::coupling
