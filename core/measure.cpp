// SPDX-License-Identifier: BSD-3-Clause
#include "core/measure.hpp"

#include <algorithm>
#include <cmath>

namespace imcol {

std::optional<LineFit> fit_line_continuous(std::span<const double> t, std::span<const double> z, double t0, double t1) {
  if (!(t1 > t0) || t.size() < 2 || t.front() > t0 || t.back() < t1) return std::nullopt;
  const double tm = 0.5 * (t0 + t1), T = t1 - t0;
  double iz = 0, iuz = 0;  // ∫ z dt and ∫ (t − tm) z dt over the window
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const double a = std::max(t[i], t0), b = std::min(t[i + 1], t1);
    if (!(b > a) || !(t[i + 1] > t[i])) continue;
    const double s = (z[i + 1] - z[i]) / (t[i + 1] - t[i]);
    const double q = z[i] + s * (tm - t[i]);  // the piece's line, z = q + s (t − tm)
    const double A = a - tm, B = b - tm;
    iz += q * (B - A) + s * (B * B - A * A) / 2;
    iuz += q * (B * B - A * A) / 2 + s * (B * B * B - A * A * A) / 3;
  }
  LineFit f;
  f.slope = iuz / (T * T * T / 12);
  f.intercept = iz / T - f.slope * tm;
  return f;
}

std::optional<PolyFit> fit_polynomial_hermite(std::span<const double> t, std::span<const double> z, std::span<const double> u,
                                              double t0, double t1, int degree, double t_ref) {
  if (!(t1 > t0) || t.size() < 2 || t.front() > t0 || t.back() < t1 || degree < 1 || degree > 2) return std::nullopt;
  // Moments m_k = ∫ z P_k(s) dt with s = 2(t − t0)/T − 1 and the Legendre polynomials P_0..P_2, by 3-point Gauss–Legendre
  // on each interpolant piece within the window (exact: a cubic times a quadratic).
  const double T = t1 - t0;
  const double gx[3] = {-0.7745966692414834, 0.0, 0.7745966692414834}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double m[3] = {0, 0, 0};
  auto i = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), t0) - t.begin());
  i = i > 0 ? i - 1 : 0;
  for (; i + 1 < t.size() && t[i] < t1; ++i) {
    const double h = t[i + 1] - t[i];
    const double a = std::max(t[i], t0), b = std::min(t[i + 1], t1);
    if (!(b > a) || !(h > 0)) continue;
    for (int q = 0; q < 3; ++q) {
      const double tq = 0.5 * (a + b) + 0.5 * (b - a) * gx[q], w = 0.5 * (b - a) * gw[q];
      const double x = (tq - t[i]) / h, x2 = x * x, x3 = x2 * x;  // cubic Hermite basis on the piece
      const double zq = (2 * x3 - 3 * x2 + 1) * z[i] + (x3 - 2 * x2 + x) * h * u[i] + (-2 * x3 + 3 * x2) * z[i + 1] + (x3 - x2) * h * u[i + 1];
      const double s = 2 * (tq - t0) / T - 1;
      m[0] += w * zq;
      m[1] += w * zq * s;
      m[2] += w * zq * 0.5 * (3 * s * s - 1);
    }
  }
  // Coefficients c_k = (2k + 1)/T · m_k of z ≈ Σ c_k P_k(s) (the P_k are orthogonal on [−1, 1], ∫P_k² ds = 2/(2k + 1)).
  const double c0 = m[0] / T, c1 = 3 * m[1] / T, c2 = degree == 2 ? 5 * m[2] / T : 0.0;
  const double s = 2 * (t_ref - t0) / T - 1, ds = 2 / T;
  PolyFit f;
  f.t_ref = t_ref;
  f.value = c0 + c1 * s + c2 * 0.5 * (3 * s * s - 1);
  f.slope = (c1 + 3 * c2 * s) * ds;
  f.accel = 3 * c2 * ds * ds;
  return f;
}

double restitution(double u_i1, double u_i2, double u_r1, double u_r2) { return -(u_r1 - u_r2) / (u_i1 - u_i2); }

double stokes_number(double m_star, double u_rel, double mu, double a_star) {
  return m_star * u_rel / (6 * 3.141592653589793238462643383279502884 * mu * a_star * a_star);
}

}  // namespace imcol
