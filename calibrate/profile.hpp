// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The interval of a parameter's objective profile where the objective stays within a threshold (factor × best).
#include <optional>
#include <utility>
#include <vector>

namespace imcol::calib {

/// `u` increasing, `f` the objective at each (+inf: failed). From the profile's smallest f outward, the first
/// crossing of `threshold` on each side, by linear interpolation in u between the last point below and the first
/// above; none on a side where the profile stays at or below the threshold up to its end.
std::pair<std::optional<double>, std::optional<double>> profile_interval(const std::vector<double>& u, const std::vector<double>& f,
                                                                         double threshold);

}  // namespace imcol::calib
