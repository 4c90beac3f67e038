// SPDX-License-Identifier: BSD-3-Clause
#include "coupling/adaptive_step.hpp"

#include <algorithm>

#include "coupling/reference_speed.hpp"

namespace imcol::coupling {

AdaptiveStep::AdaptiveStep(const Scene& sc, double h, const FlowStep& first)
    : sc_(sc), h_(h), dt_(first.dt), dt_min_(first.dt), dt_max_(first.dt) {
  active_ = sc.flow.adaptive_step && first.limit != StepLimit::given;
  const double nu = sc.fluid->viscosity / sc.fluid->density;
  cap_ = std::max(first.dt, 0.5 * h * h / nu);
  cfl_ = first.cfl;
  double tau_p = relaxation_time(sc, 0);
  for (std::size_t m = 1; m < sc.spheres.size(); ++m) tau_p = std::min(tau_p, relaxation_time(sc, m));
  tau_cap_ = std::max(first.dt, sc.flow.tau_p_fraction * tau_p);
  active_ = active_ && cfl_ > 0;  // a step set by τ_p or the viscous limit at rest stays
}

bool AdaptiveStep::separating(std::span<const double> u) const {
  if (sc_.spheres.size() == 2) return u[1] > u[0];  // the gap z2 − z1 − a1 − a2 grows
  if (sc_.wall) return u[0] < 0;                     // the wall lies at larger z (gap = z_wall − z − a)
  return true;                                       // no contact ahead
}

double AdaptiveStep::rule(double u) const {
  const double dt = u > 0 ? cfl_ * h_ / u : cap_;
  return std::min({dt, tau_cap_, cap_});
}

double AdaptiveStep::next(std::span<const double> z, std::span<const double> u, double u_fluid, bool blended) {
  if (!active_) return dt_;
  ++steady_;
  const double u_e = reference_speed(sc_, z, u).u;
  double dt = dt_;
  if (const double shorter = rule(u_e); shorter < (1 - kShrinkTolerance) * dt_) {
    dt = shorter;
  } else if (steady_ >= kSteadySteps && !blended && separating(u)) {
    const double target = rule(std::max(u_e, u_fluid / kFluidToSphereSpeed));
    if (target >= kGrowFrom * dt_) dt = std::min(target, kGrowBy * dt_);
  }
  if (dt != dt_) {
    dt_ = dt;
    steady_ = 0;
    ++changes_;
    dt_min_ = std::min(dt_min_, dt);
    dt_max_ = std::max(dt_max_, dt);
  }
  return dt_;
}

}  // namespace imcol::coupling
