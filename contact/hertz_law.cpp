// SPDX-License-Identifier: BSD-3-Clause
#include "contact/hertz_law.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "contact/formulas.hpp"
#include "core/errors.hpp"

namespace imcol::contact {

namespace {
constexpr double kAlphaMax = 20;  // e(20) ≈ 3e-3

// Classical RK4 at a fixed step: the contact lasts 3.2 (α = 0) to ~40 (α = 20) time units; h = 5e-5 puts e within
// 1e-9 of its converged value (the x^{1/4} kink at x = 0 limits the order there).
TsujiImpact integrate(double alpha) {
  constexpr double h = 5e-5;
  auto acc = [alpha](double x, double v) {
    if (x <= 0) return 0.0;
    return -std::max(0.0, x * std::sqrt(x) + alpha * std::sqrt(std::sqrt(x)) * v);
  };
  double x = 0, v = 1, t = 0, x_max = 0;
  for (long n = 0; n < 100000000L; ++n) {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    const double x_new = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double v_new = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (x_new <= 0 && v_new < 0) {
      // The last stretch is force-free (the clip acts before x = 0 when α > 0; the elastic part vanishes there when
      // α = 0): the crossing is where the straight line from (t, x) at speed v_new meets 0.
      return {-v_new, t + x / -v_new, x_max};
    }
    x = x_new;
    v = v_new;
    t += h;
    x_max = std::max(x_max, x);
  }
  throw std::runtime_error("tsuji_impact: no separation");
}
}  // namespace

TsujiImpact tsuji_impact(double alpha) { return integrate(alpha); }

double tsuji_min_e() {
  static const double e = integrate(kAlphaMax).e;
  return e;
}

namespace {
/// The root of tsuji_impact(α).e = e (e in [tsuji_min_e(), 1)).
double solve_tsuji_alpha(double e) {
  // e(α) falls monotonically. Bracket the root next to the closed-form estimate, then Illinois steps.
  const double L = std::log(e);
  auto f = [e](double a) { return integrate(a).e - e; };
  double a = std::min(kAlphaMax, -std::sqrt(5.0) * L / std::sqrt(L * L + pi * pi)), fa = f(a);
  if (fa == 0) return a;
  double b = a, fb = fa;
  while (fa * fb > 0) {  // step away from a towards the root, 20 % at a time, until the sign changes
    b = fa > 0 ? std::min(kAlphaMax, 1.2 * b) : 0.8 * b;
    fb = b > 0 ? f(b) : 1 - e;
  }
  for (int it = 0; it < 100 && std::abs(b - a) > 1e-14 * std::max(a, b); ++it) {
    const double c = (a * fb - b * fa) / (fb - fa), fc = f(c);
    if (fc == 0) return c;
    if (fc * fb < 0) {
      a = b;
      fa = fb;
    } else {
      fa *= 0.5;  // Illinois: halve the stale end's value
    }
    b = c;
    fb = fc;
    if (std::abs(fc) < 1e-12) break;  // the integration itself is good to ~1e-9
  }
  return b;
}

/// α by e, computed once per e in a process (a sweep builds one law per point with the same e_dry). Bounded: a
/// process that meets more than kMaxCached values of e starts again.
class AlphaCache {
 public:
  double get(double e) {
    {
      std::lock_guard<std::mutex> lock(m_);
      if (auto it = alpha_.find(e); it != alpha_.end()) return it->second;
    }
    const double a = solve_tsuji_alpha(e);  // outside the lock: a few ms, the same value in every thread
    std::lock_guard<std::mutex> lock(m_);
    if (alpha_.size() >= kMaxCached) alpha_.clear();
    alpha_.emplace(e, a);
    return a;
  }

 private:
  static constexpr std::size_t kMaxCached = 4096;
  std::mutex m_;
  std::map<double, double> alpha_;
};
}  // namespace

double tsuji_alpha(double e) {
  if (!(e > 0 && e <= 1)) throw std::domain_error("tsuji_alpha: e must be in (0, 1]");
  if (e == 1) return 0;
  if (e < tsuji_min_e()) throw std::domain_error("tsuji_alpha: e below what alpha <= 20 gives");
  static AlphaCache cache;
  return cache.get(e);
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
