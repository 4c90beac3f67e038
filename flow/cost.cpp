// SPDX-License-Identifier: BSD-3-Clause
#include "flow/cost.hpp"

#include <algorithm>
#include <cmath>
#include <unistd.h>

#include "core/errors.hpp"

namespace imcol::flow {

namespace {
// Measured on this kernel (coupled runs at 16 cells/D, one core): one application of Q costs ~20 ns per vertex and
// level at 14 000 vertices, growing like V^0.7 as the levels' arrays leave the caches (45 ns at 45 000, 80 ns at
// 100 000; taken to level off at 5×, memory bound) and down to half that on tiny grids; a step's explicit part
// costs half an application. The dense LU ~1 ns per n³.
constexpr double kQPerVertex = 20e-9;  // s, at kQReferenceVertices
constexpr double kQReferenceVertices = 14e3;
constexpr double kLuPerCube = 1e-9;    // s
double q_per_vertex(double vertices) { return kQPerVertex * std::clamp(std::pow(vertices / kQReferenceVertices, 0.7), 0.5, 5.0); }
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
  c.seconds_per_q = q_per_vertex(c.vertices) * c.vertices;
  c.seconds_explicit = 0.5 * c.seconds_per_q;
  c.seconds_per_step = step_seconds(c, moving, kTypicalGmresIterations);
  return c;
}

double ring_points(const Settings& s, double d) { return std::max(2.0, std::ceil(M_PI * 0.5 * d / (s.ring_spacing * s.h))); }

double step_seconds(const CostEstimate& c, bool moving, double iterations) {
  return c.seconds_explicit + c.seconds_per_q * (moving ? 3.0 + iterations : 2.0);
}

double block_seconds(const CostEstimate& c, double n) { return n * c.seconds_per_q + kLuPerCube * n * n * n; }

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
