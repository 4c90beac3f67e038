#pragma once
// Number formatting shared by the commands' tables and CSV files.
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

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

}  // namespace imcol
