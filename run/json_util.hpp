// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A measured value or JSON null ("not measured"; JSON has no NaN or infinity either).
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

namespace imcol::run {

inline nlohmann::ordered_json or_null(const std::optional<double>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

inline nlohmann::ordered_json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); }

inline nlohmann::ordered_json finite_or_null(const std::optional<double>& v) { return v ? finite_or_null(*v) : nlohmann::ordered_json(nullptr); }

}  // namespace imcol::run
