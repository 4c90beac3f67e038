// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a work-precision ladder's rows tell (study/work_precision.hpp): the observed orders (least-squares slopes of
// log error against log rtol, or the direct step, and against log steps) and the cheapest settings per target error.
#include <optional>
#include <utility>
#include <vector>

#include "study/work_precision.hpp"

namespace imcol::study {

/// Least-squares slope of log10(y) against log10(x); none below three points.
std::optional<double> loglog_slope(const std::vector<std::pair<double, double>>& xy);

/// Per configuration, the slopes over the rows whose error lies above `floor`.
std::vector<ObservedOrder> observed_orders(const std::vector<LadderConfig>& configs, const std::vector<WorkPrecisionRow>& rows,
                                           double floor);

/// For errors 1e-3, 1e-6, 1e-9: the fastest row that reaches it and keeps it at every tighter rung.
std::vector<CheapestSetting> cheapest_settings(const std::vector<WorkPrecisionRow>& rows);

}  // namespace imcol::study
