#include "core/measure.hpp"

#include <cmath>

namespace imcol {

std::optional<LineFit> fit_line(std::span<const double> t, std::span<const double> z, double t0, double t1) {
  // Centred sums for accuracy.
  double st = 0, sz = 0;
  int n = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0 && t[i] <= t1) {
      st += t[i];
      sz += z[i];
      ++n;
    }
  if (n < 2) return std::nullopt;
  const double tm = st / n, zm = sz / n;
  double stt = 0, stz = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0 && t[i] <= t1) {
      stt += (t[i] - tm) * (t[i] - tm);
      stz += (t[i] - tm) * (z[i] - zm);
    }
  if (stt <= 0) return std::nullopt;
  LineFit f;
  f.slope = stz / stt;
  f.intercept = zm - f.slope * tm;
  f.samples = n;
  return f;
}

double restitution(double u_i1, double u_i2, double u_r1, double u_r2) { return -(u_r1 - u_r2) / (u_i1 - u_i2); }

double stokes_number(double m_star, double u_rel, double mu, double a_star) {
  return m_star * u_rel / (6 * 3.141592653589793238462643383279502884 * mu * a_star * a_star);
}

}  // namespace imcol
