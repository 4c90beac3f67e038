// SPDX-License-Identifier: BSD-3-Clause
#include "contact/tables.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace imcol::contact {

LogTable::LogTable(std::function<double(double)> f, std::function<double(double)> dfdx, double x_min, double x_max, int n)
    : f_fn_(std::move(f)), dfdx_fn_(std::move(dfdx)), x_min_(x_min), x_max_(x_max), du_(std::log(x_max / x_min) / (n - 1)) {
  if (!(x_min > 0) || !(x_max > x_min) || n < 2) throw std::invalid_argument("LogTable: bad range");
  f_.assign(n, 0.0);
  g_.assign(n, 0.0);
  ready_ = std::make_unique<std::atomic<bool>[]>(n);
  for (int i = 0; i < n; ++i) ready_[i].store(false, std::memory_order_relaxed);
}

LogTable::LogTable(const double (*nodes)[2], double x_min, double x_max, int n)
    : x_min_(x_min), x_max_(x_max), du_(std::log(x_max / x_min) / (n - 1)) {
  if (!(x_min > 0) || !(x_max > x_min) || n < 2) throw std::invalid_argument("LogTable: bad range");
  f_.resize(n);
  g_.resize(n);
  ready_ = std::make_unique<std::atomic<bool>[]>(n);
  for (int i = 0; i < n; ++i) {
    f_[i] = nodes[i][0];
    g_[i] = nodes[i][1];
    ready_[i].store(true, std::memory_order_relaxed);
  }
}

double LogTable::node_x(double x_min, double x_max, int n, int i) {
  const double du = std::log(x_max / x_min) / (n - 1);
  return i == n - 1 ? x_max : x_min * std::exp(static_cast<double>(i) * du);
}

void LogTable::ensure(std::size_t i) const {
  if (ready_[i].load(std::memory_order_acquire) && ready_[i + 1].load(std::memory_order_acquire)) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  for (std::size_t k = i; k <= i + 1; ++k) {
    if (ready_[k].load(std::memory_order_relaxed)) continue;
    const double x = node_x(x_min_, x_max_, static_cast<int>(f_.size()), static_cast<int>(k));
    f_[k] = f_fn_(x);
    g_[k] = x * dfdx_fn_(x);
    ready_[k].store(true, std::memory_order_release);
  }
}

std::size_t LogTable::nodes_computed() const {
  std::size_t n = 0;
  for (std::size_t k = 0; k < f_.size(); ++k) n += ready_[k].load(std::memory_order_acquire);
  return n;
}

void LogTable::locate(double x, std::size_t& i, double& s) const {
  double u = std::log(std::clamp(x, x_min_, x_max_) / x_min_) / du_;
  i = std::min(static_cast<std::size_t>(u), f_.size() - 2);
  s = u - static_cast<double>(i);
  ensure(i);
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
