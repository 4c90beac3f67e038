// SPDX-License-Identifier: BSD-3-Clause
#include "model/pair.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "contact/formulas.hpp"

namespace imcol::model {

using contact::pi;

double sphere_volume(double a) { return 4.0 / 3.0 * pi * a * a * a; }

namespace {
// Dry restitution of the pair (choice): the scene's contact.e_dry, else the smaller of the two materials' values.
double pair_e_dry(const Scene& sc, Target target) {
  if (sc.contact.e_dry >= 0) return sc.contact.e_dry;
  double e = 1.0;
  bool any = false;
  auto take = [&](const std::optional<double>& v) { if (v) { e = any ? std::min(e, *v) : *v; any = true; } };
  take(sc.spheres[0].e_dry);
  if (target == Target::sphere) take(sc.spheres[1].e_dry);
  if (sc.wall) take(sc.wall->e_dry);
  return e;
}
}  // namespace

PairGeometry::PairGeometry(const Scene& sc) {
  target = sc.two_spheres() ? Target::sphere : (sc.wall ? Target::wall : Target::none);
  n_spheres = sc.spheres.size();
  if (sc.fluid) {
    mu = sc.fluid->viscosity;
    rho_f = sc.fluid->density;
  }
  for (std::size_t m = 0; m < n_spheres; ++m) {
    a[m] = 0.5 * sc.spheres[m].diameter;
    mp[m] = sc.spheres[m].density * sphere_volume(a[m]);
    mf[m] = rho_f * sphere_volume(a[m]);
  }
  D = 2 * a[0];
  const auto& s1 = sc.spheres[0];
  if (target == Target::sphere) {
    const auto& s2 = sc.spheres[1];
    a_star = contact::reduced(a[0], a[1]);
    m_star = contact::reduced(mp[0], mp[1]);
    E_star = contact::effective_modulus(s1.youngs_modulus, s1.poisson_ratio, s2.youngs_modulus, s2.poisson_ratio);
    initial_gap = s2.position - s1.position - a[0] - a[1];
  } else {
    a_star = a[0];
    m_star = mp[0];
    if (sc.wall) E_star = contact::effective_modulus(s1.youngs_modulus, s1.poisson_ratio, sc.wall->youngs_modulus, sc.wall->poisson_ratio);
    initial_gap = sc.wall ? sc.wall->position - s1.position - a[0] : std::numeric_limits<double>::infinity();
  }
  e_dry = pair_e_dry(sc, target);
  delta_ss_m = sc.contact.delta_ss * D;
  // A start inside the contact zone (the reader admits it only while approaching): the zone is
  // shortened to the initial gap, so that the contact law stores no energy at t = 0 and the contact begins.
  start_inside = has_target() && sc.has(Effect::elastic) && initial_gap <= delta_ss_m;
  if (start_inside) delta_ss_m = initial_gap;
  u_ref = std::max({std::abs(s1.velocity), n_spheres > 1 ? std::abs(sc.spheres[1].velocity) : 0.0, 1e-3});
  u_rel0 = has_target() ? s1.velocity - (n_spheres > 1 ? sc.spheres[1].velocity : 0.0) : 0.0;
  // The gap matters on the scale of the contact, not of the sphere: use the Hertz indentation at
  // the initial approach speed (or the lubrication cutoff if smaller), so that atol does not limit
  // the accuracy of e.
  gap_scale = D;
  if (has_target()) {
    if (sc.has(Effect::lubrication)) gap_scale = std::min(gap_scale, sc.lubrication.cutoff * D);
    if (sc.has(Effect::elastic) && u_rel0 != 0)
      gap_scale = std::min(gap_scale, contact::hertz_max_indentation(m_star, std::abs(u_rel0), E_star, a_star));
  }
}

}  // namespace imcol::model
