// SPDX-License-Identifier: BSD-3-Clause
#include "core/errors.hpp"

#include <cstdio>

namespace imcol {

namespace {
/// Control characters (from quoted keys or string values such as "a\nb") written as escapes,
/// so that every message stays on one line.
std::string printable(std::string s) {
  std::string out;
  out.reserve(s.size());
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out;
}

std::string compose(const std::string& where, const std::string& key, const std::string& problem) {
  std::string s = where;
  if (!key.empty()) s += (s.empty() ? "" : ": ") + std::string("key '") + key + "'";
  if (!s.empty()) s += ": ";
  return s + problem;
}
}  // namespace

InputError::InputError(std::string where, std::string key, const std::string& problem)
    : std::runtime_error(compose(printable(where), printable(key), printable(problem))),
      where_(printable(std::move(where))),
      key_(printable(std::move(key))),
      problem_(printable(problem)) {}

}  // namespace imcol
