// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The blend between the analytic and the simulated fluid forces (MODEL.md (6.10), §2.5, §5), with the `flow`
// effect: f_SL = H(δ/δ_SL) f_THR + (1 − H) f_SIM, H a smoothstep on [0, 2δ_SL] (1 at contact, ½ at δ_SL).
// It applies after the force terms: it scales the slots of the fluid terms (TermSlot::fluid: drag, lubrication,
// added mass, history) and the blended masses (TermMass::blended: the history force's) by H and adds (1 − H) f_rest, f_rest = f_SIM + M_A a_flow; M_A, the implicit added-mass
// estimate standing for f_SIM's, stays in the mass matrix (its (1 − H) share when the added-mass effect is not listed).
#include <array>
#include <cstddef>
#include <vector>

#include "core/scene.hpp"
#include "model/added_mass_term.hpp"
#include "model/evaluation.hpp"
#include "model/force_term.hpp"
#include "model/pair.hpp"

namespace imcol::model {

/// The simulated fluid force over one flow step (MODEL.md §5): per sphere, the flow kernel's force with the
/// model's added-mass estimate removed, f_rest = f_SIM + M_A a_flow, linear in t between (t0, f0) and (t1, f1)
/// (extrapolated linearly outside). The model adds (1 − H) f_rest and keeps M_A implicit in its mass matrix.
struct SimulatedForce {
  double t0 = 0, t1 = 1;
  std::array<double, 2> f0{}, f1{};
  double at(double t, std::size_t m) const {
    const double w = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;
    return f0[m] + w * (f1[m] - f0[m]);
  }
};

/// The slots the blend weighs: the fluid terms' forces (TermSlot::fluid) and the blended masses (TermMass::blended),
/// each in registration order.
struct FluidSlots {
  FluidSlots() = default;
  explicit FluidSlots(const ForceTerms& terms);
  /// The fluid terms' forces summed (f_THR without acceleration parts), N.
  double force(const SphereForces& f) const;
  /// The blended masses summed, kg.
  double mass(const SphereForces& f) const;

  std::vector<std::size_t> forces, masses;
};

/// H at this gap (m) for δ_SL (m): 1 − (3x² − 2x³), x = gap/(2δ_SL) clamped to [0, 1].
double blend_weight(double gap, double delta_sl_m);

class FlowBlend {
 public:
  FlowBlend(const Scene& sc, const PairGeometry& p, const ForceTerms& terms);
  /// Sets ev.H and blends ev's forces and masses (the force terms done); M is the implicit added-mass estimate at ev.gap.
  void apply(double t, const SimulatedForce& sim, const AddedMassMatrix& M, Evaluation& ev) const;
  /// Whether the estimate M_A is implicit (flow.added_mass_estimate); otherwise f_SIM is used explicitly.
  bool estimate() const { return estimate_; }
  Choices choices() const;
  /// The `model` block's line without the flow effect.
  static Choices uncoupled_choices();

 private:
  double delta_sl_m_ = 0;  // δ_SL, m
  std::size_t n_spheres_ = 1;
  bool has_target_ = false, added_mass_listed_ = false, estimate_ = true, lagrangian_pair_ = false;
  FluidSlots slots_;
};

}  // namespace imcol::model
