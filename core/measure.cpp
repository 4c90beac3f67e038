#include "core/measure.hpp"

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

double restitution(double u_i1, double u_i2, double u_r1, double u_r2) { return -(u_r1 - u_r2) / (u_i1 - u_i2); }

double stokes_number(double m_star, double u_rel, double mu, double a_star) {
  return m_star * u_rel / (6 * 3.141592653589793238462643383279502884 * mu * a_star * a_star);
}

}  // namespace imcol
