// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Added mass f_AM (MODEL.md §2.2, seed (6.8)). Its acceleration part is moved to the left-hand side, a mass matrix
// on the velocities (kg); its velocity part is a force (N):
//   `seed`        per sphere: its mass m_AM,m = ½ m_f,m (1 + 3W) on its own dU_m/dt, force (3/4) m_f,m U_m (U_rel/a*) dW/dδ**;
//   `lagrangian`  (choice, pair only) kinetic energy T = Σ ½ (m_p,m + ½ m_f,m) U_m² + ½ A(δ) U_rel²,
//                 A = (3/2) m_f* W(δ**), m_f* = (1/m_f,1 + 1/m_f,2)⁻¹: mass matrix [[M1+A, −A], [−A, M2+A]],
//                 forces ±½ A' U_rel²/a*. The same as (6.8) for a wall; for a pair it conserves momentum and, in
//                 an ideal fluid, the relative energy.
#include <array>

#include "core/scene.hpp"
#include "model/force_term.hpp"
#include "model/pair.hpp"
#include "model/wall_function.hpp"

namespace imcol::model {

/// The added-mass matrix the model keeps implicit (kg): [[m11, m12], [m12, m22]].
struct AddedMassMatrix {
  double m11 = 0, m22 = 0, m12 = 0;
};

/// The added mass's form for a scene: the seed's per-sphere ½ m_f (1 + 3W) or the lagrangian pair matrix.
struct AddedMassForm {
  AddedMassForm(const Scene& sc, const PairGeometry& p);
  /// The added-mass matrix at this gap (m); W = 0 without a target.
  AddedMassMatrix matrix(double gap) const;

  WallFunction wall;
  std::array<double, 2> mf{};  // kg
  double mf_star = 0;          // reduced fluid mass, kg
  double a_star = 0;           // m
  std::size_t n_spheres = 1;
  bool has_target = false, lagrangian_pair = false;
};

/// The added-mass term of a scene that lists the effect.
std::unique_ptr<ForceTerm> make_added_mass_term(const Scene& sc, const PairGeometry& p);

}  // namespace imcol::model
