#include "flow/cost.hpp"

#include <algorithm>
#include <cmath>
#include <unistd.h>

#include "core/errors.hpp"

namespace imcol::flow {

CostEstimate estimate_cost(const Settings& s, std::span<const double> diameters, bool moving) {
  CostEstimate c;
  c.vertices = double(s.nr + 1) * double(s.nz + 1) * s.levels;
  for (double d : diameters) c.body_points += std::max(2.0, std::ceil(M_PI * 0.5 * d / (s.ring_spacing * s.h)));
  if (s.wall_z)  // the wall's rings: ~nr on the finest level, ~nr/2 on each coarser one
    c.body_points += (s.nr + (s.levels - 1) * (s.nr / 2 - 1)) / s.ring_spacing;
  const double q_bytes = 8.0 * (2 * c.body_points) * (2 * c.body_points);
  c.bytes = 100.0 * c.vertices + q_bytes * (moving ? 18.0 : 2.0);
  c.seconds_per_step = c.vertices * 5e-8 * (moving ? 2.0 : 1.0);
  return c;
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
