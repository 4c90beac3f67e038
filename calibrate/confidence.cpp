// SPDX-License-Identifier: BSD-3-Clause
#include "calibrate/confidence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace imcol::calib {

double erf_inverse(double y) {
  if (!(y > -1 && y < 1)) return y == 1 ? INFINITY : y == -1 ? -INFINITY : std::numeric_limits<double>::quiet_NaN();
  // Start: Winitzki's approximation (relative error below 2e-3), then Newton on erf(x) - y, erf'(x) = 2/sqrt(pi) e^{-x^2}.
  constexpr double a = 0.147, pi = 3.14159265358979323846;
  const double l = std::log(1 - y * y), t = 2 / (pi * a) + l / 2;
  double x = std::copysign(std::sqrt(std::sqrt(t * t - l / a) - t), y);
  for (int i = 0; i < 50; ++i) {
    const double step = (std::erf(x) - y) / (2 / std::sqrt(pi) * std::exp(-x * x));
    x -= step;
    if (std::abs(step) <= 1e-16 * std::max(1.0, std::abs(x))) break;
  }
  return x;
}

double chi2_1_quantile(double confidence) {
  const double x = erf_inverse(confidence);
  return 2 * x * x;
}

double confidence_factor(double confidence, std::size_t n, std::size_t p) {
  if (n <= p) return std::numeric_limits<double>::infinity();
  return 1 + chi2_1_quantile(confidence) / static_cast<double>(n - p);
}

}  // namespace imcol::calib
