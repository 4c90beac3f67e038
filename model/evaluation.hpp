// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One evaluation of the model's right-hand side at (t, y): the kinematics, each term's force on each sphere, and
// the velocity mass matrix (MODEL.md §2). Each term fills its own slot (model/force_term.hpp); CollisionModel sums
// the slots in registration order.
#include <array>
#include <cstddef>

namespace imcol::model {

/// The most force terms a model holds (the slots of SphereForces).
inline constexpr std::size_t kMaxTerms = 8;

/// Forces acting on one sphere (N along z). With the `flow` effect the fluid terms are the blended ones that act,
/// H × (analytic term), and `simulated` is (1 − H) f_SIM (MODEL.md (6.10)).
struct SphereForces {
  std::array<double, kMaxTerms> term{};  // each term's force by its slot, N along z
  std::array<double, kMaxTerms> mass{};  // each term's share of the mass matrix's diagonal on this sphere, kg
  double simulated = 0;
  double implicit_added_mass = 0;  // the implicit added-mass force when no term holds it (flow without added_mass), N
  double accel = 0;  // m/s^2
  double f_thr = 0;  // the analytic fluid force f_THR unblended, incl. its acceleration parts (reporting)
  double f_sim = 0;  // the flow kernel's force f_SIM, reconstructed with the current acceleration (reporting)
};

struct Evaluation {
  double gap = 0;    // m
  double u_rel = 0;  // m/s, U1 − U2 (> 0 approaching)
  std::array<double, 2> z{}, u{};
  std::array<double, 2> m_eff{};  // diagonal of the velocity mass matrix: m_p + the terms' masses + m_pair, kg
  double m_couple = 0;            // its off-diagonal entry (lagrangian pair added mass), kg
  double m_pair = 0;              // the lagrangian pair added mass A on both diagonals, kg
  double H = 1;                     // blend weight of f_THR (MODEL.md §2.5); 1 without the flow effect
  std::array<double, 2> f_rest{};   // SimulatedForce at t (flow effect), N
  std::array<double, 2> thr_base{}, m_blended_full{};  // unblended f_THR without acceleration parts, N; blended masses, kg
  /// Solves the 2×2 mass system for the accelerations given the forces g (inline: it is on the right-hand side's path).
  std::array<double, 2> accelerations(const std::array<double, 2>& g, std::size_t n) const {
    if (n == 1) return {g[0] / m_eff[0], 0.0};
    const double det = m_eff[0] * m_eff[1] - m_couple * m_couple;
    return {(m_eff[1] * g[0] - m_couple * g[1]) / det, (m_eff[0] * g[1] - m_couple * g[0]) / det};
  }
  std::array<SphereForces, 2> f{};
};

}  // namespace imcol::model
