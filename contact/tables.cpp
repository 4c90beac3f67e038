#include "contact/tables.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace imcol::contact {

LogTable::LogTable(const std::function<double(double)>& f, const std::function<double(double)>& dfdx, double x_min,
                   double x_max, int n)
    : x_min_(x_min), x_max_(x_max), du_(std::log(x_max / x_min) / (n - 1)) {
  if (!(x_min > 0) || !(x_max > x_min) || n < 2) throw std::invalid_argument("LogTable: bad range");
  f_.resize(n);
  g_.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = x_min * std::exp(i * du_);
    if (i == n - 1) x = x_max;
    f_[i] = f(x);
    g_[i] = x * dfdx(x);
  }
}

void LogTable::locate(double x, std::size_t& i, double& s) const {
  double u = std::log(std::clamp(x, x_min_, x_max_) / x_min_) / du_;
  i = std::min(static_cast<std::size_t>(u), f_.size() - 2);
  s = u - static_cast<double>(i);
}

double LogTable::value(double x) const {
  std::size_t i;
  double s;
  locate(x, i, s);
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
  const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
  return h00 * f_[i] + h10 * du_ * g_[i] + h01 * f_[i + 1] + h11 * du_ * g_[i + 1];
}

double LogTable::derivative(double x) const {
  std::size_t i;
  double s;
  locate(x, i, s);
  // d/ds of the Hermite basis, then d/dx = (1/(x du)) d/ds.
  const double d00 = 6 * s * s - 6 * s, d10 = 3 * s * s - 4 * s + 1;
  const double d01 = -6 * s * s + 6 * s, d11 = 3 * s * s - 2 * s;
  const double dfds = d00 * f_[i] + d10 * du_ * g_[i] + d01 * f_[i + 1] + d11 * du_ * g_[i + 1];
  return dfds / (std::clamp(x, x_min_, x_max_) * du_);
}

}  // namespace imcol::contact
