// SPDX-License-Identifier: BSD-3-Clause
#include "flow/cost.hpp"

#include <algorithm>
#include <cmath>
#include <unistd.h>

#include "core/errors.hpp"

namespace imcol::flow {

namespace {
// CPU time per vertex (all levels), fitted to the run's own counts of steps, applications of Q and snapshots over the
// 39 shipped coupled runs at 16–32 cells/D (6 600–56 000 vertices; Release, GCC 12, one core of the project's machine;
// docs/performance.md §7), then raised by 10 % to centre the estimate's scatter on the measured times. One application
// of Q costs 6–16 ns a vertex from scene to scene (not from the axial FFT's factors): that spread is the estimate's.
constexpr double kStepPerVertex = 30e-9;   // s, a step's own work, bodies still relative to the grid (fitted 25–30)
constexpr double kMovingStepPerVertex = 36e-9;  // s, the same with bodies moving on it (their point rows rebuilt)
constexpr double kQPerVertex = 10.5e-9;    // s, one application of Q
constexpr double kLuPerCube = 0.2e-9;      // s per n³ of a dense LU
constexpr double kFieldPerVertex = 0.8e-6; // s, one flow-field snapshot (pressure solve, CSV text, VTK)
}  // namespace

CostEstimate estimate_cost(const Settings& s, std::span<const double> diameters, bool moving) {
  CostEstimate c;
  c.vertices = double(s.nr + 1) * double(s.nz + 1) * s.levels;
  for (double d : diameters) {
    const double p = ring_points(s, d);
    c.body_points += p;
    c.sphere_points = std::max(c.sphere_points, p);
  }
  if (s.wall_z)  // the wall's rings: ~nr on the finest level, ~nr/2 on each coarser one
    c.wall_points = (s.nr + (s.levels - 1) * (s.nr / 2 - 1)) / s.ring_spacing;
  c.body_points += c.wall_points;
  const double q_bytes = 8.0 * (2 * c.body_points) * (2 * c.body_points);
  c.bytes = 100.0 * c.vertices + q_bytes * (moving ? 18.0 : 2.0);
  c.seconds_per_q = kQPerVertex * c.vertices;
  c.seconds_explicit = (moving ? kMovingStepPerVertex : kStepPerVertex) * c.vertices;
  c.seconds_per_step = step_seconds(c, moving, kTypicalGmresIterations);
  c.seconds_per_field = kFieldPerVertex * c.vertices;
  return c;
}

double ring_points(const Settings& s, double d) { return std::max(2.0, std::ceil(M_PI * 0.5 * d / (s.ring_spacing * s.h))); }

double step_applications(bool moving, double iterations) { return moving ? 1.0 + iterations : 0.0; }

double step_seconds(const CostEstimate& c, bool moving, double iterations) {
  return c.seconds_explicit + c.seconds_per_q * step_applications(moving, iterations);
}

double block_seconds(const CostEstimate& c, double n) { return block_seconds(c, n, n); }

double block_seconds(const CostEstimate& c, double n, double applications) {
  return applications * c.seconds_per_q + kLuPerCube * n * n * n;
}

double later_block_applications(const Settings& s, double points) {
  return s.block_probe_stride > 0 ? 2 * std::min(points, static_cast<double>(s.block_probe_stride)) : 2 * points;
}

std::string memory_refusal(const CostEstimate& c) {
  const double phys = physical_memory_bytes();
  if (!(phys > 0 && c.bytes > 0.5 * phys)) return {};
  return "needs about " + fmt_number(c.bytes / 1e9) + " GB (" + fmt_number(c.vertices) + " vertices, " + fmt_number(c.body_points) +
         " body points), more than half of this machine's " + fmt_number(phys / 1e9) + " GB";
}

double physical_memory_bytes() {
  const double pages = double(::sysconf(_SC_PHYS_PAGES)), size = double(::sysconf(_SC_PAGE_SIZE));
  return pages > 0 && size > 0 ? pages * size : 0.0;
}

}  // namespace imcol::flow
