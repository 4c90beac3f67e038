// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A double as a TOML float for an override: 17 significant digits, so that the scene reader gets the same double.
#include <cstdio>
#include <string>

namespace imcol::calib {

inline std::string float_text(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  std::string s(b);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // "3" would be a TOML integer
  return s;
}

}  // namespace imcol::calib
