// SPDX-License-Identifier: BSD-3-Clause
#include "coupling/reference_speed.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "contact/formulas.hpp"
#include "flow/flow_scene.hpp"

namespace imcol::coupling {

namespace {
double drag_coefficient(double re) { return flow::standard_drag_coefficient(std::min(re, 1500.0)); }
/// U_ref from centres z and velocities vel, `when` naming them in the source ("initial", "present").
ReferenceSpeed speed_bound(const Scene& sc, std::span<const double> z, std::span<const double> vel, const char* when);
}  // namespace

double terminal_speed(double D, double rho_p, double rho_f, double mu, double g) {
  // φ = C_D Re/24 on the standard curve (C_D = 24/Re as Re → 0)
  return contact::terminal_speed(D, rho_p, rho_f, mu, g, [](double re) { return re > 0 ? drag_coefficient(re) * re / 24 : 1.0; });
}

ReferenceSpeed reference_speed(const Scene& sc) {
  std::array<double, 2> z{}, u{};
  for (std::size_t m = 0; m < sc.spheres.size() && m < 2; ++m) {
    z[m] = sc.spheres[m].position;
    u[m] = sc.spheres[m].velocity;
  }
  return speed_bound(sc, std::span<const double>(z.data(), sc.spheres.size()), std::span<const double>(u.data(), sc.spheres.size()),
                     "initial");
}

ReferenceSpeed reference_speed(const Scene& sc, std::span<const double> z, std::span<const double> u) {
  return speed_bound(sc, z, u, "present");
}

namespace {
ReferenceSpeed speed_bound(const Scene& sc, std::span<const double> z, std::span<const double> vel, const char* when) {
  ReferenceSpeed best;
  const bool gravity = sc.has(Effect::gravity) && sc.gravity != 0;
  const double rho_f = sc.fluid->density, mu = sc.fluid->viscosity;
  for (std::size_t m = 0; m < sc.spheres.size(); ++m) {
    const auto& s = sc.spheres[m];
    const double u0 = std::abs(vel[m]);
    double u = u0;
    std::ostringstream why;
    why.precision(3);
    why << "the " << when << " speed of sphere " << m + 1;
    if (gravity && s.density != rho_f) {
      const double ut = terminal_speed(s.diameter, s.density, rho_f, mu, sc.gravity);
      double fall = std::numeric_limits<double>::infinity();
      const bool toward_target = (s.density - rho_f) * sc.gravity > 0;  // + is toward the target
      if (sc.spheres.size() == 1 && sc.wall && toward_target) {
        const double L = std::max(0.0, sc.wall->position - z[m] - 0.5 * s.diameter);
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
}  // namespace

}  // namespace imcol::coupling
