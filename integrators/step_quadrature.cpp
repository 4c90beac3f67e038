// SPDX-License-Identifier: BSD-3-Clause
#include "integrators/step_quadrature.hpp"

namespace imcol {

void StepQuadrature::restart(double t, std::span<const double> y) {
  if (!active()) return;
  if (q_.empty()) q_.assign(n_, 0.0);
  w_.assign(n_, 0.0);
  sys_.quadrature_rhs(t, y, w_);
  t0_ = t1_ = t;
  q0_ = q_;
  w0_ = w_;
}

void StepQuadrature::advance(double t1, std::span<const double> y1, std::span<const double> y_mid) {
  if (!active() || !(t1 > t1_)) return;
  t0_ = t1_;
  q0_ = q_;
  w0_ = w_;
  const double h = t1 - t0_;
  wm_.assign(n_, 0.0);
  sys_.quadrature_rhs(t0_ + 0.5 * h, y_mid, wm_);
  sys_.quadrature_rhs(t1, y1, w_);
  for (std::size_t k = 0; k < n_; ++k) q_[k] = q0_[k] + h / 6 * (w0_[k] + 4 * wm_[k] + w_[k]);
  t1_ = t1;
}

void StepQuadrature::end_at(double tau, std::span<const double> y_tau) {
  if (!active() || !(tau < t1_)) return;
  const auto q = at(tau);
  q_.assign(q.begin(), q.end());
  sys_.quadrature_rhs(tau, y_tau, w_);
  t1_ = tau;
}

std::span<const double> StepQuadrature::at(double tau) {
  const double h = t1_ - t0_;
  if (!(h > 0) || tau >= t1_) return q_;
  const double s = (tau - t0_) / h;
  // Cubic Hermite basis on [0, 1] for values and (scaled) slopes.
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
  out_.resize(n_);
  for (std::size_t k = 0; k < n_; ++k) out_[k] = h00 * q0_[k] + h10 * h * w0_[k] + h01 * q_[k] + h11 * h * w_[k];
  return out_;
}

}  // namespace imcol
