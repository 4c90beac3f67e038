// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Numbers as text for CSV files: printf's %.<digits>g (what a stream with setprecision(digits) writes), by
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

}  // namespace imcol
