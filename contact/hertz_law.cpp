// SPDX-License-Identifier: BSD-3-Clause
#include "contact/hertz_law.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "contact/formulas.hpp"
#include "contact/table_data.hpp"
#include "core/errors.hpp"

namespace imcol::contact {

namespace {

/// e(α) at α by the shipped nodes: the 6-point Lagrange (quintic) interpolant on the uniform grid α_i = i Δα.
double tabulated_e(double alpha) {
  using table_data::tsuji_n, table_data::tsuji_e_nodes;
  const double da = table_data::tsuji_alpha_max / (tsuji_n - 1), u = alpha / da;
  const int i0 = std::clamp(static_cast<int>(std::floor(u)) - 2, 0, tsuji_n - 6);
  double e = 0;
  for (int j = 0; j < 6; ++j) {
    double l = 1;
    for (int k = 0; k < 6; ++k)
      if (k != j) l *= (u - (i0 + k)) / (j - k);
    e += l * tsuji_e_nodes[i0 + j];
  }
  return e;
}

}  // namespace

double tsuji_min_e() { return table_data::tsuji_e_nodes[table_data::tsuji_n - 1]; }

double tsuji_alpha(double e) {
  if (!(e > 0 && e <= 1)) throw std::domain_error("tsuji_alpha: e must be in (0, 1]");
  if (e == 1) return 0;
  if (e < tsuji_min_e()) throw std::domain_error("tsuji_alpha: e below what alpha <= 20 gives");
  // e(α) falls monotonically: the nodes' interval that holds e, then bisection on the interpolant within it.
  using table_data::tsuji_n, table_data::tsuji_e_nodes;
  const double* first = tsuji_e_nodes;
  const auto i = static_cast<int>(std::upper_bound(first, first + tsuji_n, e, std::greater<>()) - first);  // e_(i−1) ≥ e > e_i
  const double da = table_data::tsuji_alpha_max / (tsuji_n - 1);
  double lo = (std::max(i, 1) - 1) * da, hi = std::min(i, tsuji_n - 1) * da;
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (tabulated_e(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

HertzLaw::HertzLaw(const ContactPair& pair) : p_(pair) {
  k_ = (4.0 / 3.0) * p_.E_star * std::sqrt(p_.a_star);
  try {
    alpha_ = tsuji_alpha(p_.e_dry);
  } catch (const std::domain_error&) {
    std::ostringstream os;
    os << "the hertz law's damping reaches e_dry down to " << tsuji_min_e() << " (now " << p_.e_dry << ")";
    throw InputError(p_.path, "contact.e_dry", os.str());
  }
  eta_ = alpha_ * std::sqrt(p_.m_star * k_);
}

double HertzLaw::force(double gap, double u_rel) const {
  const double xi = p_.delta_ss_m - gap;
  if (!(xi > 0)) return 0.0;
  return std::max(0.0, k_ * xi * std::sqrt(xi) + eta_ * std::sqrt(std::sqrt(xi)) * u_rel);
}

void HertzLaw::begin_contact(double, double u_rel) {
  const double cap = hertz_contact_time(p_.m_star, std::abs(u_rel), p_.E_star, p_.a_star) / kContactSteps;
  contact_max_step_ = U_c_ ? std::min(contact_max_step_, cap) : cap;
  if (!U_c_) U_c_ = u_rel;
}

std::vector<std::pair<std::string, std::string>> HertzLaw::choices() const {
  std::ostringstream a;
  a.precision(6);
  a << alpha_;
  return {{"contact.hertz", "F = (4/3) E* sqrt(a*) xi^1.5 + eta xi^0.25 dxi/dt, xi = delta_ss*D - gap, clipped at 0"},
          {"contact.dissipation", "nonlinear viscous (Tsuji et al. 1992): eta = alpha sqrt(m* k), alpha from e_dry"},
          {"contact.alpha", a.str()}};
}

std::vector<LawValue> HertzLaw::summary() const {
  std::optional<double> W, xi, tc;
  if (U_c_) {
    const double U = std::abs(*U_c_);
    xi = hertz_max_indentation(p_.m_star, U, p_.E_star, p_.a_star);
    W = hertz_force(p_.E_star, p_.a_star, *xi);
    tc = hertz_contact_time(p_.m_star, U, p_.E_star, p_.a_star);
  }
  // W_o_N, xi_max_m, t_c_s: the undamped Hertz values at the first impact speed (references, not measurements).
  return {{"W_o_N", W}, {"xi_max_m", xi}, {"t_c_hertz_s", tc}, {"alpha", alpha_}, {"eta_N_s_m-1.25", eta_}};
}

}  // namespace imcol::contact
