// SPDX-License-Identifier: BSD-3-Clause
#include "run/progress_estimate.hpp"

#include <algorithm>

namespace imcol::run {

void ProgressEstimate::add(double wall, double done) {
  // Keep the newest point and, as the anchor of the rate, the newest one at least kWindow older than it.
  if (!points_.empty() && wall - points_.back().first < 0.05) {
    points_.back() = {wall, done};  // closer than 50 ms: replace, so that the deque stays short
  } else {
    points_.emplace_back(wall, done);
  }
  while (points_.size() > 2 && wall - points_[1].first >= kWindow) points_.pop_front();
}

std::optional<double> ProgressEstimate::seconds_left(double total) const {
  if (points_.size() < 2) return std::nullopt;
  const auto& [w0, d0] = points_.front();
  const auto& [w1, d1] = points_.back();
  if (!(d1 > d0) || !(w1 > w0)) return std::nullopt;
  return std::max(0.0, total - d1) * (w1 - w0) / (d1 - d0);
}

std::optional<double> eta_seconds(const ProgressEstimate& estimate, double elapsed, double done, double total) {
  if (done >= total) return 0.0;
  if (const auto left = estimate.seconds_left(total)) return left;
  if (!(done > 0)) return std::nullopt;
  return std::max(0.0, elapsed) * (total - done) / done;
}

std::optional<Progress> ProgressTimer::at(double done, double total) {
  const double wall = seconds_since(start_);
  estimate_.add(wall, done);
  if (!(total > 0)) return std::nullopt;
  const auto eta = eta_seconds(estimate_, wall, done, total);
  if (!eta) return std::nullopt;
  return Progress{done, total, *eta};
}

std::optional<Progress> ProgressFollower::poll() {
  const auto [done, total] = meter_.read();
  const auto p = timer_.at(done, total);
  if (!p || !(done > last_done_)) return std::nullopt;
  last_done_ = done;
  return p;
}

}  // namespace imcol::run
