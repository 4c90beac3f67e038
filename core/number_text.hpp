// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Numbers as text for CSV files and scene overrides: printf's %.<digits>g (what a stream with setprecision(digits) writes), by
// std::to_chars, which is several times faster than the stream and allocates nothing.
#include <charconv>
#include <string>

namespace imcol {

/// Appends v to out as %.<digits>g.
inline void append_number(std::string& out, double v, int digits) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::general, digits);
  out.append(b, r.ptr);
}

/// v as a TOML float for a scene override (--set's value syntax): the shortest text that reads back to the same
/// double, with ".0" where the digits alone would be a TOML integer.
inline std::string toml_float(double v) {
  char b[40];
  std::string s(b, std::to_chars(b, b + sizeof b, v).ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

}  // namespace imcol
