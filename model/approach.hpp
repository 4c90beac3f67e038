// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Whether a scene can ever collide, decided at t = 0 (MODEL.md §1: +z points from the impact sphere to its target).
// U_rel = U1 − U2 (> 0: approaching). Without gravity every force of the model is the fluid's or the solids' reaction
// to the spheres' own motion through fluid at rest (drag, lubrication, added mass, history, f_SIM); such forces slow a
// sphere, they never turn it around. A collision is impossible for certain when:
//   sphere–wall: U1 ≤ 0 and the net weight (m_p − m_f) g does not point to the wall (no gravity, or g ≤ 0 for a
//     heavy sphere, g ≥ 0 for a light one); the wall's added-mass gradient pushes a receding sphere further out;
//   sphere pair: no gravity, U1 ≤ 0 ≤ U2 (neither moves toward the other), and either nothing couples the spheres
//     (no lubrication, added_mass or flow: each sphere decelerates on its own) or the spheres are identical (the
//     equation for U_rel is then odd in U_rel and U_rel cannot change sign).
// Not certain, so integrated: a pair moving the same way (drag slows the leader first and the trailing sphere can
// catch up; unequal coupled spheres likewise), any pair under gravity, a sphere whose weight points to the wall.
#include <optional>
#include <string>

#include "core/scene.hpp"

namespace imcol::model {

/// Why the scene can never collide ("never approaching: …"), or nothing if a collision is possible or not excluded.
std::optional<std::string> never_approaching(const Scene& sc);

}  // namespace imcol::model
