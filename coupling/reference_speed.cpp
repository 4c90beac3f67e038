// SPDX-License-Identifier: BSD-3-Clause
#include "coupling/reference_speed.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "contact/formulas.hpp"
#include "flow/flow_scene.hpp"

namespace imcol::coupling {

namespace {
double drag_coefficient(double re) { return flow::standard_drag_coefficient(std::min(re, 1500.0)); }
}  // namespace

double terminal_speed(double D, double rho_p, double rho_f, double mu, double g) {
  // φ = C_D Re/24 on the standard curve (C_D = 24/Re as Re → 0)
  return contact::terminal_speed(D, rho_p, rho_f, mu, g, [](double re) { return re > 0 ? drag_coefficient(re) * re / 24 : 1.0; });
}

ReferenceSpeed reference_speed(const Scene& sc) {
  ReferenceSpeed best;
  const bool gravity = sc.has(Effect::gravity) && sc.gravity != 0;
  const double rho_f = sc.fluid->density, mu = sc.fluid->viscosity;
  for (std::size_t m = 0; m < sc.spheres.size(); ++m) {
    const auto& s = sc.spheres[m];
    const double u0 = std::abs(s.velocity);
    double u = u0;
    std::ostringstream why;
    why.precision(3);
    why << "the initial speed of sphere " << m + 1;
    if (gravity && s.density != rho_f) {
      const double ut = terminal_speed(s.diameter, s.density, rho_f, mu, sc.gravity);
      double fall = std::numeric_limits<double>::infinity();
      const bool toward_target = (s.density - rho_f) * sc.gravity > 0;  // + is toward the target
      if (sc.spheres.size() == 1 && sc.wall && toward_target) {
        const double L = std::max(0.0, sc.wall->position - s.position - 0.5 * s.diameter);
        const double g_eff = std::abs(s.density - rho_f) * std::abs(sc.gravity) / (s.density + 0.5 * rho_f);
        fall = std::sqrt(u0 * u0 + 2 * g_eff * L);
      }
      if (std::min(ut, fall) > u0) {
        u = std::min(ut, fall);
        why.str("");
        if (fall < ut) why << "the speed of sphere 1's fall to the wall (terminal speed " << ut << " m/s)";
        else why << "the terminal speed of sphere " << m + 1;
      }
    }
    if (u > best.u || m == 0) best = {u, why.str()};
  }
  return best;
}

}  // namespace imcol::coupling
