// SPDX-License-Identifier: BSD-3-Clause
#include "run/energy_budget.hpp"

#include <algorithm>
#include <cmath>

namespace imcol::run {

using model::ForceKind;
using model::kAllForceKinds;
using model::kForceKinds;

namespace {

/// The sample at time t (an event's sample for the phase ends; the nearest one at or before t otherwise).
std::size_t sample_at(const Track& tr, double t) {
  std::size_t i = tr.first_at_or_after(t);
  if (i >= tr.t.size()) return tr.t.size() - 1;
  if (tr.t[i] > t && i > 0) --i;
  return i;
}

/// One phase between samples i0 and i1, with the impact kinetic energy `ke_ref` as the unit of `dissipated`.
EnergyPhase phase(const Track& tr, BudgetPhase name, std::size_t i0, std::size_t i1, double ke_ref) {
  EnergyPhase p;
  p.phase = name;
  p.t0_s = tr.t[i0];
  p.t1_s = tr.t[i1];
  p.ke_spheres_J = {tr.ke_spheres[i0], tr.ke_spheres[i1]};
  p.ke_added_J = {tr.ke_added[i0], tr.ke_added[i1]};
  double sum = 0;
  const double d_added = tr.ke_added[i1] - tr.ke_added[i0];
  for (std::size_t k = 0; k < kForceKinds; ++k) {
    const double w = tr.work[i1][k] - tr.work[i0][k];
    sum += w;
    p.work_J[k] = w;
    // The added mass's own kinetic energy is not lost: its dissipation is what its work does not put there.
    const double d = kAllForceKinds[k] == ForceKind::added_mass ? -(w + d_added) : -w;
    p.dissipated_J[k] = d;
    p.dissipated_per_impact_energy[k] = ke_ref > 0 ? d / ke_ref : 0.0;
  }
  const double d_ke = tr.ke_spheres[i1] - tr.ke_spheres[i0];
  p.closure_J = d_ke - sum;
  p.closure_per_impact_energy = ke_ref > 0 ? (d_ke - sum) / ke_ref : 0.0;
  return p;
}

}  // namespace

std::optional<EnergyBudget> energy_budget(const Track& tr, const CollisionTimes& times) {
  if (tr.work.size() != tr.t.size() || tr.t.empty()) return std::nullopt;
  const std::size_t a0 = sample_at(tr, times.t_from), c0 = sample_at(tr, times.t_in);
  const std::size_t r0 = sample_at(tr, times.t_sep.value_or(times.t_next)), r1 = sample_at(tr, times.t_next);
  // The unit: the largest kinetic energy of the approach (the impact as a camera sees it, before the film brakes it).
  double ke_ref = 0;
  for (std::size_t i = a0; i <= c0; ++i) ke_ref = std::max(ke_ref, tr.ke_spheres[i] + tr.ke_added[i]);
  EnergyBudget b;
  b.impact_kinetic_energy_J = ke_ref;
  b.phases.push_back(phase(tr, BudgetPhase::approach, a0, c0, ke_ref));
  b.phases.push_back(phase(tr, BudgetPhase::contact, c0, r0, ke_ref));
  if (times.t_sep) b.phases.push_back(phase(tr, BudgetPhase::rebound, r0, r1, ke_ref));
  b.phases.push_back(phase(tr, BudgetPhase::collision, a0, r1, ke_ref));
  return b;
}

}  // namespace imcol::run
