// SPDX-License-Identifier: BSD-3-Clause
#include "contact/ramp_law.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "contact/formulas.hpp"
#include "core/errors.hpp"

namespace imcol::contact {

double RampLaw::force(double gap, double) const {
  if (W_now_ == 0) return 0.0;
  return factor_ * W_now_ * ramp_F(gap / p_.delta_ss_m, beta_now_);
}

void RampLaw::begin_contact(double t, double u_rel) {
  // W_o and β frozen at the relative speed U_c of the δ_SS crossing (MODEL.md §2.4).
  const double eps_max = hertz_max_indentation(p_.m_star, u_rel, p_.E_star, p_.a_star);
  W_now_ = hertz_force(p_.E_star, p_.a_star, eps_max);
  if (p_.beta > 0) {
    beta_now_ = p_.beta;
  } else if (eps_max < 1.25 * p_.delta_ss_m) {
    beta_now_ = energy_consistent_beta(p_.delta_ss_m, eps_max);
  } else {
    std::ostringstream os;
    os << "at t = " << t << " s the Hertz indentation " << eps_max << " m for U_c = " << u_rel
       << " m/s cannot be stored by the ramp over delta_ss*D = " << p_.delta_ss_m << " m: set delta_ss (units of D) above "
       << std::setprecision(3) << 0.8 * eps_max / p_.D << " in the scene's [contact] table (now " << p_.delta_ss
       << "), or lower the impact speed";
    throw InputError(p_.path, "contact.delta_ss", os.str());
  }
  factor_ = 1.0;
  const double cap = hertz_contact_time(p_.m_star, std::abs(u_rel), p_.E_star, p_.a_star) / kContactSteps;
  contact_max_step_ = W_o_ ? std::min(contact_max_step_, cap) : cap;
  ramp_on_gap_ = p_.delta_ss_m * std::min(1.0, kRampTail / beta_now_);
  if (!W_o_) {
    W_o_ = W_now_;
    beta_ = beta_now_;
  }
}

double RampLaw::max_step(double gap, double u_rel) const {
  const double above = gap - ramp_on_gap_;
  if (!(above > 0)) return contact_max_step_;
  return std::max(contact_max_step_, 0.25 * above / std::abs(u_rel));
}

std::optional<std::string> RampLaw::start_inside_refusal(double u_rel) const {
  const double eps_max = hertz_max_indentation(p_.m_star, u_rel, p_.E_star, p_.a_star);
  if (p_.beta > 0 || eps_max < 1.25 * p_.delta_ss_m) return std::nullopt;
  std::ostringstream os;
  os << "the sphere starts inside the contact zone, " << p_.delta_ss_m << " m from contact, where the ramp cannot store the impact:"
     << " the Hertz indentation at U = " << u_rel << " m/s is " << eps_max << " m; start at a gap above " << 0.8 * eps_max
     << " m, approach more slowly, or set contact.law = \"hertz\" (the Hertz law stores any impact from the initial gap)";
  return os.str();
}

std::vector<std::pair<std::string, std::string>> RampLaw::choices() const {
  std::ostringstream beta;
  beta.precision(6);
  beta << p_.beta;
  return {{"contact.ramp", "F(x) = (exp(beta(1-x))-1)/(exp(beta)-1)"},
          {"contact.beta", p_.beta > 0 ? beta.str() : "energy-consistent"},
          {"contact.dissipation", "e_dry^2 on unloading"}};
}

std::vector<LawValue> RampLaw::summary() const { return {{"W_o_N", W_o_}, {"beta", beta_}}; }

}  // namespace imcol::contact
