// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Numbers as text for CSV files and scene overrides: printf's %.<digits>g (what a stream with setprecision(digits) writes).
// Up to 12 digits the significant digits come from a scaling by one or two tabled powers of ten (10^k, |k| ≤ 44: a
// few roundings) and an integer rounding, several times faster than std::to_chars with a precision; a value whose
// scaled form lies within 16 units of its last place of a rounding tie or of a power of ten, and every other case
// (inf, nan, subnormals, magnitudes beyond ~1e±36, more digits) is written by std::to_chars, so the text is
// %.<digits>g's in every case.
#include <charconv>
#include <string>

namespace imcol {

/// Appends v to out as %.<digits>g by std::to_chars.
inline void append_number_exact(std::string& out, double v, int digits) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::general, digits);
  out.append(b, r.ptr);
}

/// Appends v to out as %.<digits>g (the fast path above where it is exact, else append_number_exact).
void append_number(std::string& out, double v, int digits);

/// v as a TOML float for a scene override (--set's value syntax): the shortest text that reads back to the same
/// double, with ".0" where the digits alone would be a TOML integer.
inline std::string toml_float(double v) {
  char b[40];
  std::string s(b, std::to_chars(b, b + sizeof b, v).ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

}  // namespace imcol
