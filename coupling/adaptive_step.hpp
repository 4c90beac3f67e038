// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The flow step re-chosen as a coupled run goes on (flow.adaptive_step; docs/coupling.md "The flow step"). The first
// step (coupling/step_rule.hpp) is Δt_0 = cfl_0 h/U_ref with U_ref what the spheres can reach from their initial state;
// a sphere that has rebounded and slowed can no longer reach it, so the run keeps the Courant number cfl_0 of the
// spheres' speed and takes U from the present state:
//   Δt(t) = min(cfl_0 h/U(t), tau_p_fraction τ_p, max(Δt_0, ½h²/ν)),
// U(t) the bound of coupling/reference_speed.hpp from the spheres' present centres and velocities (the speed; with
// gravity the fall to the wall, capped by the terminal speed). cfl_0 is the rule's value at the initial Re, at most
// the value at any later, slower Re: the stability margin of the first step is kept. Never longer than the viscous
// step ½h²/ν unless the first step was (Crank–Nicolson damps the grid's shortest modes poorly beyond it).
// The step shrinks at once when U(t) asks for a shorter one. It grows only while the spheres move apart beyond the
// blend's reach (H = 0, gap ≥ 2 δ_SL): every approach and rebound runs at the step of the last apex, the first bounce
// at the first step, where the measures of e read the rebound (a step grown right after the first rebound moved
// gondret_st100's e, fit_distance/joseph_2001, by 0.0035). It grows after kSteadySteps steps at the present one, when
// the step for max(U(t), u_f/2) is kGrowFrom times it or more, by kGrowBy at most at a time (AB2 with a variable step
// stays stable for ratios below 1 + √2); u_f is the fluid's largest speed on the finest level after the last step
// (relative to the grid): a rebounding sphere runs into the wake of its approach, where the fluid moved at 5 U
// (gondret_st742, first rebound; with u_f/4 here the fluid's Courant number reached 1.65 against the fixed step's
// 1.23). The fluid's speed does not shrink the step: the squeezed film exceeds 4 U briefly at every contact, where the
// first step's margin holds (shrinking there moved gondret_st742's e by 0.003).
#include <span>

#include "core/scene.hpp"
#include "coupling/step_rule.hpp"

namespace imcol::coupling {

inline constexpr double kFluidToSphereSpeed = 2;  // growth: the fluid's largest speed allowed per U (u_f/2 above)
inline constexpr long kSteadySteps = 10;          // steps at a step before it may grow
inline constexpr double kGrowFrom = 1.2;          // the rule's step over the present one that lets it grow
inline constexpr double kGrowBy = 1.5;            // the largest growth at a time
inline constexpr double kShrinkTolerance = 1e-9;  // a step within this fraction of the rule's is kept

class AdaptiveStep {
 public:
  /// The first step `first` (flow_step(sc, h)); adaptive when flow.adaptive_step and the rule (not flow.dt) gave it.
  AdaptiveStep(const Scene& sc, double h, const FlowStep& first);
  bool active() const { return active_; }
  /// The step (s) for the coming flow step from the spheres' present centres z (m) and velocities u (m/s), the
  /// fluid's largest speed u_fluid (m/s) after the last step, and whether the gap is within the blend's reach (H > 0).
  double next(std::span<const double> z, std::span<const double> u, double u_fluid, bool blended = false);
  /// The rule's step for a reference speed u (m/s), capped as above.
  double rule(double u) const;
  /// Whether the spheres move apart (the gap to the target or the wall grows; always without one).
  bool separating(std::span<const double> u) const;
  double dt() const { return dt_; }
  double dt_min() const { return dt_min_; }
  double dt_max() const { return dt_max_; }
  long changes() const { return changes_; }

 private:
  const Scene& sc_;
  double h_ = 0, cap_ = 0, tau_cap_ = 0;  // finest spacing (m); the longest step, and τ_p's limit (s)
  double cfl_ = 0;                       // the first step's Courant number of U_ref
  double dt_ = 0, dt_min_ = 0, dt_max_ = 0;
  long steady_ = 0, changes_ = 0;  // steps at the present step; step changes
  bool active_ = false;
};

}  // namespace imcol::coupling
