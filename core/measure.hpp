// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Measurements on a trajectory (MODEL.md §3): least-squares velocities, restitution, Stokes numbers.
#include <optional>
#include <span>

namespace imcol {

struct LineFit {
  double slope = 0;      // m/s
  double intercept = 0;  // m
};

/// Least-squares line fitted to the piecewise-linear interpolant of the samples over [t0, t1]
/// (continuous least squares): unlike the discrete fit it varies smoothly as the window moves.
/// Samples must be sorted in t and cover [t0, t1].
std::optional<LineFit> fit_line_continuous(std::span<const double> t, std::span<const double> z, double t0, double t1);

/// A polynomial of degree ≤ 2 fitted by least squares to the piecewise cubic Hermite interpolant of samples
/// (positions z, m, and their derivatives u, m/s) over [t0, t1], given about t_ref:
/// z(t) ≈ value + slope (t − t_ref) + ½ accel (t − t_ref)².
struct PolyFit {
  double t_ref = 0;   // s
  double value = 0;   // m
  double slope = 0;   // m/s
  double accel = 0;   // m/s² (0 for a line)
};

/// Continuous least squares of degree 1 (a line) or 2 (constant acceleration) on [t0, t1]. The Hermite interpolant
/// is exact for cubics, so the fit does not depend on where the samples lie once they resolve the motion; a line or a
/// parabola is reproduced exactly. Samples must be sorted in t and cover [t0, t1].
std::optional<PolyFit> fit_polynomial_hermite(std::span<const double> t, std::span<const double> z, std::span<const double> u,
                                              double t0, double t1, int degree, double t_ref);

/// e = −(U_r1 − U_r2)/(U_i1 − U_i2)  (seed eq. 6.1)
double restitution(double u_i1, double u_i2, double u_r1, double u_r2);

/// St_B = m* U_rel / (6π μ a*²)  (seed eq. 6.2; for a wall m* = m, a* = a gives the particle St)
double stokes_number(double m_star, double u_rel, double mu, double a_star);

}  // namespace imcol
