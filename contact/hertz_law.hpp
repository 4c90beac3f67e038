// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Hertz contact with nonlinear viscous damping (Tsuji, Tanaka & Ishida, Powder Technol. 71 (1992) 239–250):
//   f_SS = k ξ^{3/2} + η ξ^{1/4} dξ/dt,   k = (4/3) E* √a*,   η = α √(m* k),   clipped at 0 (never pulls),
// on the overlap ξ = δ_SS − gap (m), dξ/dt = U_rel. imcol's convention is the ramp's: the contact force acts below the
// gap δ_SS (contact.delta_ss × D, the solids' "touching" distance, which stands for roughness), so the solids touch at
// gap = δ_SS and the overlap is counted from there; a start inside the zone shortens δ_SS to the initial gap (ξ = 0 at
// t = 0), so the law stores any impact.
// The force is clipped: where the damping part, negative on unloading, exceeds the elastic part, f_SS = 0 (a viscous
// contact would otherwise pull the pair together just before separation).
// Damping: with this form e depends on α alone, not on the impact speed. α is set so that the dimensionless problem
//   x'' = −max(0, x^{3/2} + α x^{1/4} x'),  x(0) = 0, x'(0) = 1   (x = ξ/L, L = (m* U²/k)^{2/5}, time in L/U)
// returns e_dry: Tsuji et al.'s α(e) relation, computed (contact/tsuji_impact.hpp, tabulated) rather than read off their graph. The
// closed form α ≈ −√5 ln e / √(ln²e + π²) used by several DEM codes is the starting guess; it is off by 2e-4 in e at
// e = 0.97 and by 0.05 at e = 0.5. A dry collision then returns e_dry (tests/test_contact_laws.cpp).
#include "contact/contact_law.hpp"
#include "contact/tsuji_impact.hpp"

namespace imcol::contact {

/// α with tsuji_impact(α).e = e (0 < e ≤ 1; 0 for e = 1); a std::domain_error below tsuji_min_e(). From the shipped
/// nodes of e(α) (contact/table_data.cpp, α ≤ 20 every 0.02, written by imcol_gen_tables from tsuji_impact): a
/// quintic interpolant inverted by bisection, a few µs; e(α) it returns is within 1e-10 of e (tests).
double tsuji_alpha(double e);
/// The smallest e tsuji_alpha reaches (α = 20).
double tsuji_min_e();

class HertzLaw : public ContactLaw {
 public:
  /// An InputError (contact.e_dry) if e_dry is below tsuji_min_e().
  explicit HertzLaw(const ContactPair& pair);
  ContactLawKind kind() const override { return ContactLawKind::hertz; }
  double force(double gap, double u_rel) const override;
  void begin_contact(double t, double u_rel) override;
  /// 1/kContactSteps of the Hertz time at the slowest impact so far, in the whole zone (the force is felt from δ_SS on).
  double max_step(double, double) const override { return contact_max_step_; }
  std::optional<std::string> start_inside_refusal(double) const override { return std::nullopt; }
  std::vector<std::pair<std::string, std::string>> choices() const override;
  std::vector<LawValue> summary() const override;

  double stiffness() const { return k_; }  // k, N/m^{3/2}
  double alpha() const { return alpha_; }
  double eta() const { return eta_; }      // η, N s/m^{5/4}

 private:
  ContactPair p_;
  double k_ = 0, alpha_ = 0, eta_ = 0;
  double contact_max_step_ = 0;  // s (0 until the first contact)
  std::optional<double> U_c_;    // the first contact's impact speed, m/s
};

}  // namespace imcol::contact
