// SPDX-License-Identifier: BSD-3-Clause
#include "calibrate/profile.hpp"

#include <algorithm>
#include <cmath>

namespace imcol::calib {

std::pair<std::optional<double>, std::optional<double>> profile_interval(const std::vector<double>& u, const std::vector<double>& f,
                                                                         double threshold) {
  if (u.empty() || u.size() != f.size()) return {};
  const std::size_t m = static_cast<std::size_t>(std::min_element(f.begin(), f.end()) - f.begin());
  // Between an inside point a and an outside point b: where the line through them reaches the threshold (at b when
  // b failed).
  auto crossing = [&](std::size_t a, std::size_t b) {
    if (!std::isfinite(f[b])) return u[b];
    return u[a] + (threshold - f[a]) / (f[b] - f[a]) * (u[b] - u[a]);
  };
  std::pair<std::optional<double>, std::optional<double>> r;
  if (!(f[m] <= threshold)) return {u[m], u[m]};  // nowhere within: an empty interval at the smallest
  for (std::size_t i = m; i-- > 0;)
    if (!(f[i] <= threshold)) {
      r.first = crossing(i + 1, i);
      break;
    }
  for (std::size_t i = m + 1; i < u.size(); ++i)
    if (!(f[i] <= threshold)) {
      r.second = crossing(i - 1, i);
      break;
    }
  return r;
}

}  // namespace imcol::calib
