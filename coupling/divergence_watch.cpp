// SPDX-License-Identifier: BSD-3-Clause
#include "coupling/divergence_watch.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/errors.hpp"

namespace imcol::coupling {

bool is_solid_contact(model::EventTag k) {
  using model::tag;
  using R = model::ModelRoot;
  return k == tag(R::contact_in) || k == tag(R::contact_out) || k == tag(R::unload) || k == tag(R::touch) || k == tag(R::start_in_contact);
}

DivergenceWatch::DivergenceWatch(const model::CollisionModel& model, const Scene& sc, std::span<const double> y0, FlowStep step)
    : model_(model), sc_(sc), n_(model.n_spheres()), step_(std::move(step)) {
  std::array<double, 2> u{};
  model_.sphere_states(y0, z0_, u);
  for (std::size_t m = 0; m < n_; ++m) {
    m_[m] = model_.mass(static_cast<int>(m));
    mf_[m] = model_.fluid_mass(static_cast<int>(m));
    e0_ += 0.5 * (m_[m] + mf_[m]) * u[m] * u[m];
  }
  g_ = sc.has(Effect::gravity) ? sc.gravity : 0.0;
  // Below the energy scale the kernel resolves, nothing is judged: ½ m_1 (1 µm/s)² (round-off motion) plus the work of
  // the spheres' net weight over one finest cell, Σ |m_m − m_f,m| |g| h (a sphere released from rest that first moves
  // a fraction of a cell against its net weight has no available energy yet).
  const double h = 2 * model_.radius(0) / sc.flow.cells_per_diameter;
  e_abs_ = 0.5 * m_[0] * 1e-12;
  for (std::size_t m = 0; m < n_; ++m) e_abs_ += std::abs((m_[m] - mf_[m]) * g_) * h;
}

double DivergenceWatch::kinetic(std::span<const double> y) const {
  std::array<double, 2> z{}, u{};
  model_.sphere_states(y, z, u);
  double k = 0;
  for (std::size_t m = 0; m < n_; ++m) k += 0.5 * m_[m] * u[m] * u[m];
  return k;
}

double DivergenceWatch::available(std::span<const double> y) const {
  std::array<double, 2> z{}, u{};
  model_.sphere_states(y, z, u);
  double w = 0;  // work of gravity and buoyancy, J
  for (std::size_t m = 0; m < n_; ++m) w += (m_[m] - mf_[m]) * g_ * (z[m] - z0_[m]);
  return e0_ + std::max(0.0, w);
}

double DivergenceWatch::speed_floor(int m, double e_avail, double dt) const {
  // plus what gravity and buoyancy alone add in one step (a sphere released from rest)
  return sc_.flow.speed_jump_floor * std::sqrt(2 * (e_avail + e_abs_) / m_[m]) + std::abs((m_[m] - mf_[m]) / m_[m] * g_) * dt;
}

bool DivergenceWatch::energy_exceeded(std::span<const double> y) const {
  return kinetic(y) > (1 + sc_.flow.energy_margin) * available(y) + e_abs_;
}

void DivergenceWatch::fail(double t, const std::string& what) const {
  std::ostringstream os;
  os << std::setprecision(4) << "the flow coupling diverged at t = " << t << " s: " << what << "; " << step_advice(step_)
     << " (if a smaller step fails sooner, the coupling's explicit fluid inertia is unstable for these spheres: docs/coupling.md "
     << "\"Divergence\")";
  throw SolverError(os.str());
}

std::string DivergenceWatch::energy_message(double t, std::span<const double> y, const std::string& then) const {
  std::ostringstream os;
  os << std::setprecision(4) << "the flow coupling diverged by t = " << t << " s: the spheres' kinetic energy " << kinetic(y)
     << " J exceeds (1 + flow.energy_margin = " << sc_.flow.energy_margin << ") x the " << available(y)
     << " J that the initial motion and gravity can supply; " << step_advice(step_) << " (then: " << then << ")";
  return os.str();
}

void DivergenceWatch::check_kernel_force(double t, double dt, const std::array<double, 2>& f, std::span<const double> y) {
  std::array<double, 2> z{}, u{};
  model_.sphere_states(y, z, u);
  const double e = available(y);
  const double gap = n_ == 2 ? z[1] - z[0] - model_.radius(0) - model_.radius(1)
                             : (sc_.wall ? sc_.wall->position - z[0] - model_.radius(0) : 1e300);
  const model::AddedMassMatrix M = model_.implicit_added_mass(gap);
  for (std::size_t m = 0; m < n_; ++m) {
    const double ma = m == 0 ? M.m11 : M.m22;
    const double du = std::abs(f[m]) * dt / (m_[m] + ma);
    const double lim = sc_.flow.speed_jump * std::max(std::abs(u[m]), speed_floor(static_cast<int>(m), e, dt));
    if (du > lim) {
      std::ostringstream os;
      os << std::setprecision(4) << "the flow kernel's force on sphere " << m + 1 << " (" << f[m] << " N) would change its speed by "
         << du << " m/s in one flow step of " << dt << " s, more than flow.speed_jump = " << sc_.flow.speed_jump << " x " << lim / sc_.flow.speed_jump
         << " m/s";
      fail(t, os.str());
    }
  }
}

void DivergenceWatch::check_step(double t0, double t1, const std::array<double, 2>& u0, std::span<const double> y1) {
  std::array<double, 2> z{}, u{};
  model_.sphere_states(y1, z, u);
  const double e = available(y1), k = kinetic(y1);
  max_ratio_ = std::max(max_ratio_, k / std::max(e, e_abs_));
  // Solid contact in the step (an event at the contact zone, or the gap inside it at its end) legitimately turns a
  // sphere around or sets a target moving within one flow step: the speed jump is not judged there.
  bool contact = false;
  for (const auto& ev : model_.events())
    if (ev.t >= t0 && ev.t <= t1 && is_solid_contact(ev.kind)) contact = true;
  const double gap = n_ == 2 ? z[1] - z[0] - model_.radius(0) - model_.radius(1)
                             : (sc_.wall ? sc_.wall->position - z[0] - model_.radius(0) : 1e300);
  if (gap <= model_.delta_ss_m()) contact = true;
  if (!contact) {
    for (std::size_t m = 0; m < n_; ++m) {
      const double lim = sc_.flow.speed_jump * std::max(std::abs(u0[m]), speed_floor(static_cast<int>(m), e, t1 - t0));
      if (std::abs(u[m]) > lim) {
        std::ostringstream os;
        os << std::setprecision(4) << "the speed of sphere " << m + 1 << " jumped from " << std::abs(u0[m]) << " to " << std::abs(u[m])
           << " m/s in one flow step (t = " << t0 << " to " << t1 << " s), more than flow.speed_jump = " << sc_.flow.speed_jump << " x "
           << lim / sc_.flow.speed_jump << " m/s";
        fail(t1, os.str());
      }
    }
  }
  if (k > (1 + sc_.flow.energy_margin) * e + e_abs_) {
    std::ostringstream os;
    os << std::setprecision(4) << "the spheres' kinetic energy " << k << " J exceeds (1 + flow.energy_margin = " << sc_.flow.energy_margin
       << ") x the " << e << " J that the initial motion and gravity can supply";
    fail(t1, os.str());
  }
}

}  // namespace imcol::coupling
