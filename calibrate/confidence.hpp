// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The profile-likelihood confidence interval's threshold for one parameter of a least-squares fit under independent
// Gaussian noise of one unknown variance, estimated from the best fit: the interval is where
//   J <= J_best * (1 + q / (n - p)),
// J the mean square residual, q the chi^2(1) quantile at the confidence C, n the residuals, p the fitted parameters
// (the time offset of a trajectory among them).
#include <cstddef>

namespace imcol::calib {

/// erf^-1(y) for y in (-1, 1) (Newton's method on std::erf from a closed-form start; to round-off).
double erf_inverse(double y);

/// The chi^2 quantile with one degree of freedom at probability C in (0, 1): q = 2 (erf^-1(C))^2 (3.841459 at 0.95).
double chi2_1_quantile(double confidence);

/// 1 + q / (n - p): the factor on the best mean square residual. Requires n > p.
double confidence_factor(double confidence, std::size_t n, std::size_t p);

}  // namespace imcol::calib
