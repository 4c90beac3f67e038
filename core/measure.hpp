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

/// e = −(U_r1 − U_r2)/(U_i1 − U_i2)  (seed eq. 6.1)
double restitution(double u_i1, double u_i2, double u_r1, double u_r2);

/// St_B = m* U_rel / (6π μ a*²)  (seed eq. 6.2; for a wall m* = m, a* = a gives the particle St)
double stokes_number(double m_star, double u_rel, double mu, double a_star);

}  // namespace imcol
