#include "coupling/step_rule.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace imcol::coupling {

namespace {
constexpr double kP0 = 5600;  // Re·N below which cfl 0.5 (docs/coupling.md "The flow step")
}  // namespace

double default_cfl(double re, int cells) { return 0.5 * std::min(1.0, std::sqrt(kP0 / std::max(re * cells, 1e-300))); }

FlowStep flow_step(const Scene& sc, double h, double u_ref) {
  FlowStep s;
  const double D = sc.spheres[0].diameter, nu = sc.fluid->viscosity / sc.fluid->density;
  s.re = u_ref * D / nu;
  std::ostringstream os;
  os.precision(3);
  if (sc.flow.dt > 0) {
    s.dt = sc.flow.dt;
    os << "flow.dt = " << s.dt << " s";
  } else {
    s.cfl = sc.flow.cfl > 0 ? sc.flow.cfl : default_cfl(s.re, sc.flow.cells_per_diameter);
    s.dt = u_ref > 0 ? s.cfl * h / u_ref : s.cfl * h * h / nu;  // at rest: a viscous step
    os << "flow.cfl = " << s.cfl;
    if (!(sc.flow.cfl > 0)) os << " (the default at Re = " << s.re << ")";
    os << ", dt = " << s.dt << " s";
  }
  s.rule = os.str();
  return s;
}

}  // namespace imcol::coupling
