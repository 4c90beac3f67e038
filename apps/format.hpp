// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Number formatting shared by the commands' tables and CSV files.
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/number_text.hpp"

namespace imcol {

/// Scientific notation with p digits after the point; "-" for a missing (non-finite) value.
inline std::string sci(double v, int p = 2) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream os;
  os << std::scientific << std::setprecision(p) << v;
  return os.str();
}

/// Fixed notation with p digits after the point.
inline std::string fixed(double v, int p) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(p) << v;
  return os.str();
}

/// A CSV cell: 12 significant digits; empty for a missing (NaN) value.
inline std::string csv_number(double v) {
  std::string s;
  if (!std::isnan(v)) append_number(s, v, 12);
  return s;
}

/// A CSV cell from a summary value: empty for null, 1/0 for a boolean, csv_number for a number, a string as is.
inline std::string csv_cell(const nlohmann::ordered_json& j) {
  if (j.is_null()) return "";
  if (j.is_boolean()) return j.get<bool>() ? "1" : "0";
  if (j.is_number()) return csv_number(j.get<double>());
  if (j.is_string()) return j.get<std::string>();
  return j.dump();
}

/// A summary number in fixed notation with p digits; "n/a" for null.
inline std::string json_num(const nlohmann::ordered_json& j, int p) { return j.is_null() ? "n/a" : fixed(j.get<double>(), p); }

/// A CSV cell from a value that may be missing: empty when it is.
inline std::string csv_cell(const std::optional<double>& v) { return v ? csv_number(*v) : std::string(); }

/// A value that may be missing in fixed notation with p digits; "n/a" when it is.
inline std::string fixed_or_na(const std::optional<double>& v, int p) { return v ? fixed(*v, p) : "n/a"; }

}  // namespace imcol
