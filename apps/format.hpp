#pragma once
// Number formatting shared by the commands' tables and CSV files.
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

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
  if (std::isnan(v)) return "";
  std::ostringstream os;
  os << std::setprecision(12) << v;
  return os.str();
}

}  // namespace imcol
