// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A measured value or JSON null ("not measured").
#include <nlohmann/json.hpp>
#include <optional>

namespace imcol::run {

inline nlohmann::ordered_json or_null(const std::optional<double>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

}  // namespace imcol::run
