// SPDX-License-Identifier: BSD-3-Clause
#include "model/flow_blend.hpp"

#include <algorithm>

namespace imcol::model {

double blend_weight(double gap, double delta_sl_m) {
  const double x = std::clamp(0.5 * gap / delta_sl_m, 0.0, 1.0);
  return 1.0 - x * x * (3 - 2 * x);
}

FlowBlend::FlowBlend(const Scene& sc, const PairGeometry& p, const ForceTerms& terms)
    : delta_sl_m_(sc.contact.delta_sl * p.D), n_spheres_(p.n_spheres), has_target_(p.has_target()),
      added_mass_listed_(sc.has(Effect::added_mass)), estimate_(sc.flow.added_mass_estimate),
      lagrangian_pair_(sc.added_mass.model == AddedMassModel::lagrangian && p.pair()), slots_(terms) {}

FluidSlots::FluidSlots(const ForceTerms& terms) {
  for (const auto& t : terms) {
    const TermSlot s = t->properties();
    if (s.fluid) forces.push_back(t->slot());
    if (s.mass == TermMass::blended) masses.push_back(t->slot());
  }
}

namespace {
double sum_of(const std::array<double, kMaxTerms>& v, const std::vector<std::size_t>& slots) {
  if (slots.empty()) return 0.0;
  double sum = v[slots[0]];
  for (std::size_t i = 1; i < slots.size(); ++i) sum += v[slots[i]];
  return sum;
}
}  // namespace

double FluidSlots::force(const SphereForces& f) const { return sum_of(f.term, forces); }
double FluidSlots::mass(const SphereForces& f) const { return sum_of(f.mass, masses); }

void FlowBlend::apply(double t, const SimulatedForce& sim, const AddedMassMatrix& M, Evaluation& ev) const {
  // f_SL = H f_THR + (1 − H) f_SIM (6.10). The acceleration parts: f_SIM's added mass is removed from it
  // (f_rest = f_SIM + M_A a) and kept implicit, so the mass matrix carries M_A in full whatever H is; the
  // history force's κ-like mass is blended like its force.
  ev.H = has_target_ ? blend_weight(ev.gap, delta_sl_m_) : 0.0;
  const double H = ev.H;
  for (std::size_t m = 0; m < n_spheres_; ++m) {
    auto& f = ev.f[m];
    ev.thr_base[m] = slots_.force(f);
    ev.m_blended_full[m] = slots_.mass(f);
    for (std::size_t s : slots_.forces) f.term[s] *= H;  // the added mass's: its velocity (dW/dδ) part
    for (std::size_t s : slots_.masses) {
      ev.m_eff[m] -= (1 - H) * f.mass[s];
      f.mass[s] *= H;
    }
    ev.f_rest[m] = sim.at(t, m);
    f.simulated = (1 - H) * ev.f_rest[m];
  }
  if (!added_mass_listed_) {
    // No analytic added mass: only the (1 − H) share standing for f_SIM's is implicit.
    ev.m_eff[0] += (1 - H) * M.m11;
    if (n_spheres_ == 2) ev.m_eff[1] += (1 - H) * M.m22;
    ev.m_couple += (1 - H) * M.m12;
  }
}

Choices FlowBlend::choices() const {
  return {{"blend.H", "smoothstep: H = 1 - (3t^2 - 2t^3), t = gap/(2 delta_sl) in [0, 1]"},
          {"blend.delta_sl_m", choice_number(delta_sl_m_)},
          {"blend.added_mass_estimate", lagrangian_pair_ ? "lagrangian pair matrix, implicit" : "1/2 m_f (1 + 3W), implicit"}};
}

Choices FlowBlend::uncoupled_choices() { return {{"blend.H", "1 (reduced-order: no f_SIM)"}}; }

}  // namespace imcol::model
