// SPDX-License-Identifier: BSD-3-Clause
#include "study/dem_replay.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace imcol::study {

double hooke_k_n(const HookeContact& c) {
  const double sqrt_r = std::sqrt(c.r_eff);
  return 16. / 15. * sqrt_r * c.Y_eff * std::pow(15. * c.m_eff * c.char_vel * c.char_vel / (16. * sqrt_r * c.Y_eff), 0.2);
}

double hooke_gamma_n(double m_eff, double k_n, double L) {
  const double L2 = L * L;
  if (!std::isfinite(L2)) return std::sqrt(4 * m_eff * k_n);  // the source's inf/inf: its limit
  return std::sqrt(4 * m_eff * k_n * L2 / (L2 + M_PI * M_PI));
}

double hooke_contact_time(const HookeContact& c) { return M_PI * std::sqrt(c.m_eff / hooke_k_n(c)); }

double viscous_stokes(const HookeContact& c, double mu, double vn) { return c.m_eff * vn / (6 * M_PI * mu * c.r_eff * c.r_eff); }

double viscous_log_e(const HookeContact& c, const ViscousRule& rule, double vn) {
  const double St = viscous_stokes(c, rule.fluid_viscosity, vn);
  if (St == 0) return std::numeric_limits<double>::infinity();
  return std::log(rule.maximum_restitution) + rule.critical_stokes / St;
}

double impact_speed_for_stokes(const HookeContact& c, double mu, double St) { return St * 6 * M_PI * mu * c.r_eff * c.r_eff / c.m_eff; }

ReplayResult replay_hooke(const HookeContact& c, const LogRestitution& L, double U, const ReplayStep& step) {
  if (!(U > 0) || !(c.m_eff > 0) || !(c.r_eff > 0) || !(c.Y_eff > 0) || !(c.char_vel > 0))
    throw std::invalid_argument("replay_hooke: U, m*, r*, Y* and the characteristic velocity must be positive");
  const double k = hooke_k_n(c);
  ReplayResult r;
  r.dt = step.dt ? *step.dt : hooke_contact_time(c) / step.steps_per_contact;
  const double half = 0.5 * r.dt / c.m_eff;
  const long max_steps = static_cast<long>(std::ceil(step.max_contact_times * hooke_contact_time(c) / r.dt));
  double delta = 0, vn = -U, F = 0;
  for (long n = 0; n < max_steps; ++n) {
    vn += half * F;
    delta -= vn * r.dt;
    if (delta <= 0) {  // apart: no force from here on
      r.separated = true;
      break;
    }
    ++r.steps;
    F = k * delta - hooke_gamma_n(c.m_eff, k, L(vn)) * vn;
    if (step.limit == ForceLimit::on && F < 0) F = 0;
    vn += half * F;
  }
  r.duration = static_cast<double>(r.steps) * r.dt;
  r.e = r.separated ? vn / U : 0;
  return r;
}

ReplayResult replay_viscous(const HookeContact& c, const ViscousRule& rule, double U, const ReplayStep& step) {
  return replay_hooke(c, [&](double vn) { return viscous_log_e(c, rule, vn); }, U, step);
}

ReplayResult replay_constant_e(const HookeContact& c, double e, double U, const ReplayStep& step) {
  const double L = e > 0 ? std::log(e) : -std::numeric_limits<double>::infinity();
  return replay_hooke(c, [L](double) { return L; }, U, step);
}

}  // namespace imcol::study
