#pragma once
// Smooth interpolation of a costly function of a positive argument on a logarithmic grid
// (cubic Hermite in u = ln x, with derivatives from the function's own derivative).
#include <functional>
#include <vector>

namespace imcol::contact {

class LogTable {
 public:
  /// Tabulates f and df/dx on n points log-spaced in [x_min, x_max].
  LogTable(const std::function<double(double)>& f, const std::function<double(double)>& dfdx, double x_min,
           double x_max, int n);
  double x_min() const { return x_min_; }
  double x_max() const { return x_max_; }
  /// Value and derivative d/dx of the interpolant; x must lie in [x_min, x_max].
  double value(double x) const;
  double derivative(double x) const;

 private:
  void locate(double x, std::size_t& i, double& s) const;
  double x_min_, x_max_, du_;
  std::vector<double> f_, g_;  // f and df/du = x df/dx at the nodes
};

}  // namespace imcol::contact
