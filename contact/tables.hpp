// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Smooth interpolation of a costly function of a positive argument on a logarithmic grid
// (cubic Hermite in u = ln x, with derivatives from the function's own derivative).
// Nodes are computed on first use (thread-safe), so a run pays only for the range it visits.
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

namespace imcol::contact {

class LogTable {
 public:
  /// Tabulates f and df/dx on n points log-spaced in [x_min, x_max].
  LogTable(std::function<double(double)> f, std::function<double(double)> dfdx, double x_min, double x_max, int n);
  /// From precomputed nodes {f(x_i), x_i f'(x_i)}, x_i = x_min (x_max/x_min)^(i/(n−1)) (shipped tables).
  LogTable(const double (*nodes)[2], double x_min, double x_max, int n);
  /// Node i of the grid and its {f, x df/dx} from the functions (what the shipped tables hold).
  static double node_x(double x_min, double x_max, int n, int i);
  double x_min() const { return x_min_; }
  double x_max() const { return x_max_; }
  /// Value and derivative d/dx of the interpolant; x must lie in [x_min, x_max].
  double value(double x) const;
  double derivative(double x) const;
  /// Nodes computed so far (for tests and diagnostics).
  std::size_t nodes_computed() const;

 private:
  void locate(double x, std::size_t& i, double& s) const;
  void ensure(std::size_t i) const;  // nodes i and i + 1
  std::function<double(double)> f_fn_, dfdx_fn_;
  double x_min_, x_max_, du_;
  mutable std::vector<double> f_, g_;  // f and df/du = x df/dx at the nodes
  mutable std::unique_ptr<std::atomic<bool>[]> ready_;
  mutable std::mutex mutex_;
};

}  // namespace imcol::contact
