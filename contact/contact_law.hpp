// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A solid contact law f_SS (MODEL.md §2.4): the force that pushes the pair apart once the gap is below δ_SS.
// The collision model owns one law, built by make_contact_law from the scene's contact.law, arms the events and
// tells the law about them: begin_contact at the inward δ_SS crossing (or at t = 0 for a start inside the zone),
// unload at U_rel = 0 in contact, end_contact at the outward δ_SS crossing.
// Adding a law: a class here in contact/, one line in make_contact_law, one name in core/choices.hpp (ContactLawKind).
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/choices.hpp"

namespace imcol::contact {

/// What a law knows of the pair (SI).
struct ContactPair {
  double m_star = 0;      // reduced mass, kg
  double E_star = 0;      // effective modulus, Pa
  double a_star = 0;      // reduced radius, m
  double e_dry = 1;       // dry restitution of the pair
  double delta_ss_m = 0;  // m: the force acts below this gap (the zone, shortened to the initial gap for a start inside it)
  double D = 0;           // m: the impact sphere's diameter, the unit of contact.delta_ss
  double delta_ss = 0;    // contact.delta_ss as the scene gives it, units of D (messages)
  double beta = 0;        // contact.beta (0: energy-consistent), the ramp's steepness
  std::string path;       // the scene file (input errors)
};

/// One named number of a law's summary block; none (null) before the first contact.
struct LawValue {
  std::string name;
  std::optional<double> value;
};

class ContactLaw {
 public:
  virtual ~ContactLaw() = default;
  virtual ContactLawKind kind() const = 0;
  /// Force magnitude pushing the pair apart (N, never negative) at the gap (m) and U_rel (m/s, > 0 approaching).
  /// Called in every phase after the first contact began, so it must vanish (or nearly) above δ_SS.
  virtual double force(double gap, double u_rel) const = 0;
  /// A contact begins at time t (s) at U_rel = u_rel > 0: freeze what the law freezes. InputError if it cannot.
  virtual void begin_contact(double t, double u_rel) = 0;
  /// U_rel = 0 inside the contact (loading → unloading).
  virtual void unload() {}
  /// The gap rises above δ_SS again.
  virtual void end_contact() {}
  /// The largest step (s) the integrator should take in contact at this gap (m) and U_rel (m/s).
  virtual double max_step(double gap, double u_rel) const = 0;
  /// A start inside the contact zone at U_rel = u_rel (the zone shortened to the initial gap): why the law cannot
  /// take it, or none.
  virtual std::optional<std::string> start_inside_refusal(double u_rel) const = 0;
  /// The law's lines of summary.json's `model` block, name → text.
  virtual std::vector<std::pair<std::string, std::string>> choices() const = 0;
  /// The law's numbers in summary.json's `contact` block (the first contact's).
  virtual std::vector<LawValue> summary() const = 0;

  /// In contact the step is at most 1/kContactSteps of the Hertz contact time at the impact speed, so that a loose
  /// rtol cannot step over the force's peak. At rtol = atol = 1e-3 without history the ramp's e is then within 1.3 %
  /// (default), 3.3 % (gg3462) and 7 % (gg3462 at 0.02 m/s) of a tight run; without a contact cap 9 % and 58 % off
  /// (tests/test_hard_cases.cpp, StepCap).
  static constexpr double kContactSteps = 5;
};

/// The law the scene names (one line per law).
std::unique_ptr<ContactLaw> make_contact_law(ContactLawKind kind, const ContactPair& pair);

}  // namespace imcol::contact
