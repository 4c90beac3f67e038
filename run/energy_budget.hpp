// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The energy budget of one collision (docs/energy.md): over its approach (from the start of the flight to the inward
// δ_SS crossing), its contact (to the outward crossing) and its rebound (to the next contact or the end of the run),
// the work of each force (model/force_work.hpp) against the change of kinetic energy, J.
//   ΔKE_spheres = Σ_k W_k  (Newton's law; `closure_J` is what is left: the integration error of the work)
//   ΔKE_spheres + ΔKE_added = Σ_{k ≠ added mass} W_k + (W_added_mass + ΔKE_added)
// The last bracket is zero for a conservative added mass (the lagrangian form): `added_mass_J` in `dissipated_J`.
// Each force's dissipation is −W_k; the sum of all of them is the loss of kinetic energy (spheres and added mass).
#include <optional>

#include "run/bounce.hpp"
#include "run/bounces.hpp"

namespace imcol::run {

/// The times that bound one collision's phases, s: the flight's start, the inward δ_SS crossing, the outward one
/// (none: no separation, the contact lasts to t_next) and the end of the rebound's flight.
struct CollisionTimes {
  double t_from = 0, t_in = 0;
  std::optional<double> t_sep;
  double t_next = 0;
};

/// The budget: the impact kinetic energy (spheres and added mass, the largest over the approach), and per phase
/// (approach, contact, rebound, collision) its times, kinetic energies at both ends, the work and dissipation of each
/// force (the latter also in units of the impact kinetic energy) and the closure. None without the work samples.
std::optional<EnergyBudget> energy_budget(const Track& tr, const CollisionTimes& times);

}  // namespace imcol::run
