// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The seed's exponential ramp (MODEL.md §2.4, choice): below the gap δ_SS,
//   f_SS = F(x) · W_o · (branch factor),  F(x) = (e^{β(1−x)} − 1)/(e^β − 1),  x = gap/δ_SS,
// W_o = (4/3) E* √a* ε_max^{3/2} the Hertz peak force at the speed U_c of the inward δ_SS crossing and β (the scene's,
// else energy-consistent: δ_SS ∫_0^1 F dx = (2/5) ε_max) frozen there; the branch factor is 1 while loading and
// e_dry² from U_rel = 0 on (unloading), so that a dry collision returns e = e_dry exactly. The force sees only the gap.
#include "contact/contact_law.hpp"

namespace imcol::contact {

class RampLaw : public ContactLaw {
 public:
  explicit RampLaw(const ContactPair& pair) : p_(pair) {}
  ContactLawKind kind() const override { return ContactLawKind::ramp; }
  double force(double gap, double u_rel) const override;
  void begin_contact(double t, double u_rel) override;
  void unload() override { factor_ = p_.e_dry * p_.e_dry; }
  /// 1/kContactSteps of the Hertz time at the slowest impact so far below ramp_on_gap_, where the force is felt; above
  /// it a quarter of the time to reach it at the current U_rel (a quarter, since the value limits the step after next).
  double max_step(double gap, double u_rel) const override;
  std::optional<std::string> start_inside_refusal(double u_rel) const override;
  std::vector<std::pair<std::string, std::string>> choices() const override;
  std::vector<LawValue> summary() const override;

  static constexpr double kRampTail = 36;  // F(x) < e^(-kRampTail) above x = kRampTail/β (e^-36 ≈ 2e-16)

 private:
  ContactPair p_;
  double W_now_ = 0, beta_now_ = 0, factor_ = 1;  // this contact's W_o (N), β and branch factor
  double contact_max_step_ = 0;                     // s (0 until the first contact)
  double ramp_on_gap_ = 0;                          // m: F < e^(-kRampTail) above this gap (set with β)
  std::optional<double> W_o_, beta_;                // the first contact's
};

}  // namespace imcol::contact
