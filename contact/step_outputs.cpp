// SPDX-License-Identifier: BSD-3-Clause
#include "contact/step_outputs.hpp"

#include <cmath>
#include <limits>

namespace imcol::contact {

double StepOutputs::hermite(double h, End a, End b, double s) {
  const double r = 1 - s;
  return (1 + 2 * s) * r * r * a.value + s * r * r * h * a.slope + s * s * (3 - 2 * s) * b.value - s * s * r * h * b.slope;
}

double StepOutputs::estimate(double h, End start, End end, double dc, double sc_value) {
  const double sc = dc / h;
  if (!(h > 0) || !(sc >= kCheckFrom && sc <= 1 - kCheckFrom)) return std::numeric_limits<double>::infinity();
  return std::abs(sc_value - hermite(h, start, end, sc)) * bubble(0.5) / bubble(sc);
}

StepOutputs::StepOutputs(double h, End start, End end, double dc, double sc_value, double tol) : h_(h), a_(start), b_(end) {
  error_ = estimate(h, start, end, dc, sc_value);
  if (!std::isfinite(error_)) return;
  const double sc = dc / h;
  correction_ = (sc_value - hermite(h, start, end, sc)) / bubble(sc);
  accepted_ = error_ <= tol;
}

double StepOutputs::value(double dt) const {
  const double s = dt / h_;
  return hermite(h_, a_, b_, s) + correction_ * bubble(s);
}

}  // namespace imcol::contact
