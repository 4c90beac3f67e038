// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Detects a coupled run that is no longer physical (docs/coupling.md "Divergence"): the flow kernel's explicit AB2
// advection breaks when the fluid's Courant number nears 1, and the partitioned f_SIM then feeds the spheres energy
// that nothing supplies. Three checks, all thresholds [flow] settings:
//   energy:      Σ ½ m_m u_m² > (1 + energy_margin) E_avail(t) + E_floor, E_floor = ½ m_1 (1 µm/s)² + Σ |m_m − m_f,m| |g| h
//                (h the finest spacing: the net weight's work over one cell, below what the kernel resolves), with
//                E_avail(t) = Σ ½ (m_m + m_f,m) u_m(0)² + max(0, Σ (m_m − m_f,m) g (z_m(t) − z_m(0)))
//                (J: the initial motion of the spheres and of the fluid they displace — more than the added mass's
//                ½ m_f — plus the work of gravity and buoyancy so far);
//   speed jump:  over a flow step without solid contact, |u_m(t_{n+1})| > speed_jump · max(|u_m(t_n)|, u_floor,m);
//   kernel kick: before the step, |(1 − H) f_rest,m| Δt / (m_m + m_A,m) > speed_jump · max(|u_m(t_n)|, u_floor,m),
//                the speed change the kernel's force alone would make in one step;
//   u_floor,m = speed_jump_floor · √(2 E_avail / m_m) + |1 − m_f,m/m_m| |g| Δt (m/s), the speed scale below which a
//   jump is not judged (the second term: what gravity and buoyancy alone add in one step).
// A failed check throws SolverError (exit 3) naming the flow coupling, the quantity, the time and the keys to change.
#include <array>
#include <span>
#include <string>

#include "model/collision_model.hpp"
#include "core/scene.hpp"
#include "coupling/step_rule.hpp"

namespace imcol::coupling {

/// Whether an event (its tag) is solid contact, one of the model's roots (the δ_SS crossings, unloading, the gap
/// closing, a start in contact): a flow step holding one is not judged by the speed jump.
bool is_solid_contact(model::EventTag kind);

class DivergenceWatch {
 public:
  /// `step`: the flow step and how it was chosen (its rule and advice go into the message, step_advice()).
  DivergenceWatch(const model::CollisionModel& model, const Scene& sc, std::span<const double> y0, FlowStep step);
  /// Before integrating [t, t + dt]: the force the kernel adds, (1 − H) f_rest on each sphere (N), at the state y.
  void check_kernel_force(double t, double dt, const std::array<double, 2>& f_acting, std::span<const double> y);
  /// After integrating [t0, t1] from y0 to y1 (y0's velocities as u0).
  void check_step(double t0, double t1, const std::array<double, 2>& u0, std::span<const double> y1);
  /// Whether the state y breaks the energy bound (used when the integrator failed, to name the real cause).
  bool energy_exceeded(std::span<const double> y) const;
  /// The message for a failure detected elsewhere (the integrator) while the energy bound is broken.
  std::string energy_message(double t, std::span<const double> y, const std::string& then) const;
  double max_energy_ratio() const { return max_ratio_; }  // largest KE / E_avail seen (reporting)

 private:
  double kinetic(std::span<const double> y) const;
  double available(std::span<const double> y) const;
  double speed_floor(int m, double e_avail, double dt) const;
  [[noreturn]] void fail(double t, const std::string& what) const;
  const model::CollisionModel& model_;
  const Scene& sc_;
  std::size_t n_ = 1;
  std::array<double, 2> z0_{}, m_{}, mf_{};
  double e0_ = 0, g_ = 0, e_abs_ = 0;
  double max_ratio_ = 0;
  FlowStep step_;
};

}  // namespace imcol::coupling
