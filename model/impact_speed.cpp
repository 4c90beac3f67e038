// SPDX-License-Identifier: BSD-3-Clause
#include "model/impact_speed.hpp"

#include <algorithm>
#include <cmath>

#include "contact/formulas.hpp"

namespace imcol::model {

namespace {

/// Terminal speed (m/s) of sphere m under gravity alone with the scene's steady drag law.
double terminal_speed(const Scene& sc, std::size_t m) {
  const auto& sp = sc.spheres[m];
  const DragLaw law = sc.drag.law;
  return contact::terminal_speed(sp.diameter, sp.density, sc.fluid->density, sc.fluid->viscosity, sc.gravity,
                                 [law](double re) { return contact::drag_factor(law, re); });
}

}  // namespace

double impact_speed_bound(const Scene& sc, const PairGeometry& p) {
  double u = std::abs(p.u_rel0);
  if (!sc.has(Effect::gravity)) return u;
  const double rho_f = sc.fluid ? sc.fluid->density : 0.0;
  double g = 0, u_drag = 0;
  for (std::size_t m = 0; m < p.n_spheres; ++m) {
    g += std::abs(sc.gravity) * std::abs(1 - rho_f / sc.spheres[m].density);
    if (sc.fluid && sc.has(Effect::drag)) u_drag += std::max(std::abs(sc.spheres[m].velocity), terminal_speed(sc, m));
  }
  u += std::sqrt(2 * g * std::max(0.0, p.initial_gap));
  return sc.fluid && sc.has(Effect::drag) ? std::min(u, std::max(u_drag, std::abs(p.u_rel0))) : u;
}

}  // namespace imcol::model
