// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The system's quadratures q' = w(t, y) (DynamicalSystem::quadrature_rhs) integrated beside the solver, step by step:
// Simpson's rule on each accepted step [t0, t1] with the solver's interpolant at its middle,
//   q(t1) = q(t0) + (t1 − t0)/6 · (w(t0) + 4 w(t½) + w(t1)),
// and cubic Hermite interpolation from (q, w) at both ends for a sample inside the step. The error per step is
// O(h⁵ w''''), below the solver's own local error at the steps it takes for its tolerance. No SUNDIALS types here.
#include <span>
#include <vector>

#include "core/system.hpp"

namespace imcol {

class StepQuadrature {
 public:
  explicit StepQuadrature(DynamicalSystem& sys) : sys_(sys), n_(sys.quadrature_size()) {}
  bool active() const { return n_ > 0; }

  /// Starts (t = 0, q = 0) or restarts (after an event changed w) at (t, y), keeping q.
  void restart(double t, std::span<const double> y);
  /// Integrates over the step from the last point to t1: y1 = y(t1), y_mid = y at the step's middle.
  void advance(double t1, std::span<const double> y1, std::span<const double> y_mid);
  /// Makes tau within the last step the last point reached (the run ends there), y_tau = y(tau).
  void end_at(double tau, std::span<const double> y_tau);
  /// q at the last point reached.
  std::span<const double> value() const { return q_; }
  /// q at tau within the last step (cubic Hermite); at its end, the value itself.
  std::span<const double> at(double tau);

 private:
  DynamicalSystem& sys_;
  std::size_t n_;
  double t0_ = 0, t1_ = 0;
  std::vector<double> q0_, w0_, q_, w_, wm_, out_;  // at the step's start, its end, its middle; the last `at`
};

}  // namespace imcol
