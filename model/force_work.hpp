// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The work of each force on the spheres, for the energy budget of a collision (docs/energy.md):
//   W_k(t) = ∫_0^t Σ_m f_k,m U_m dt'   (J; the integrand, the power, in W),
// f_k,m the full force of kind k on sphere m (the added-mass and history forces with their acceleration parts).
// Newton's law for each sphere then gives Δ(Σ ½ m_p U²) = Σ_k W_k exactly; the integrator carries W_k as quadratures.
#include <array>
#include <cstddef>
#include <vector>

#include "model/evaluation.hpp"

namespace imcol::model {

enum class ForceKind { drag, lubrication, added_mass, history, contact, gravity, simulated };
inline constexpr std::size_t kForceKinds = 7;
inline constexpr std::array<ForceKind, kForceKinds> kAllForceKinds = {ForceKind::drag,    ForceKind::lubrication, ForceKind::added_mass,
                                                                      ForceKind::history, ForceKind::contact,     ForceKind::gravity,
                                                                      ForceKind::simulated};

/// "drag", "lubrication", "added_mass", "history", "contact", "gravity", "simulated" (summary.json's names).
const char* to_string(ForceKind k);

/// Where each kind's force is: the slots (SphereForces::term) of the terms of that kind, in registration order
/// (model/force_term.hpp kind_slots). `simulated` is the flow blend's (SphereForces::simulated).
using KindSlots = std::array<std::vector<std::size_t>, kForceKinds>;

/// The force of kind k on one sphere, N: its terms' slots summed; without one, 0 (the added mass: the implicit
/// added-mass force the flow blend leaves when no term holds it).
double force_of(const SphereForces& f, ForceKind k, const KindSlots& slots);

/// The power of each kind of force on the n spheres of an evaluated state (CollisionModel::evaluate), W.
std::array<double, kForceKinds> force_powers(const Evaluation& ev, std::size_t n, const KindSlots& slots);

}  // namespace imcol::model
