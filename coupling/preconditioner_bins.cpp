// SPDX-License-Identifier: BSD-3-Clause
#include "coupling/preconditioner_bins.hpp"

#include <algorithm>
#include <cmath>

namespace imcol::coupling {

double krylov_tolerance_factor(double krylov_tol) {
  return (1 + std::max(0.0, -std::log10(krylov_tol))) / 9;
}

int automatic_bins(double steps, double block_columns, double krylov_tol) {
  if (!(block_columns > 0) || !(steps > 0)) return 4;
  const double c = kGmresBinIterations * krylov_tolerance_factor(krylov_tol);
  const double best = std::pow(0.6 * c * steps / block_columns, 1 / 1.6);
  const double power = std::clamp(std::round(std::log2(std::max(best, 1.0))), 2.0, 6.0);
  return static_cast<int>(std::lround(std::exp2(power)));
}

double bin_iterations(int bins, double krylov_tol) {
  return kGmresBinIterations * krylov_tolerance_factor(krylov_tol) * std::pow(std::max(1, bins), -0.6);
}

}  // namespace imcol::coupling
