// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A table of entries by name (the materials, the fluids): lookup and the list of names for error messages, and the
// reading of its CSV file's rows and numbers.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace imcol {

template <class Entry>
class NamedTable {
 public:
  const Entry* find(const std::string& name) const {
    auto it = by_name_.find(name);
    return it == by_name_.end() ? nullptr : &it->second;
  }
  /// The names, sorted.
  std::vector<std::string> name_list() const {
    std::vector<std::string> out;
    for (const auto& [k, v] : by_name_) out.push_back(k);
    return out;
  }
  /// Comma-separated, for error messages.
  std::string names() const {
    std::string s;
    for (const auto& [k, v] : by_name_) s += (s.empty() ? "" : ", ") + k;
    return s;
  }

 protected:
  std::map<std::string, Entry> by_name_;
};

/// The number in a CSV cell, or nullopt for an empty cell. Throws InputError (`where`, `column`) for anything else that
/// is not a finite number.
inline std::optional<double> csv_number(const std::string& cell, const std::string& where, const std::string& column) {
  if (cell.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  if (end == cell.c_str() || *end != '\0' || !std::isfinite(v)) throw InputError(where, column, "not a number: '" + cell + "'");
  return v;
}

/// Calls `row(where, line)` for each data line of the CSV file `path` ("FILE:LINE", the line): blank lines and lines
/// starting with '#' are skipped, and the first other line must be a header starting with `header`. `what` names the
/// table in the error for a file that cannot be opened.
inline void read_csv_rows(const std::string& path, const std::string& what, const std::string& header,
                          const std::function<void(const std::string& where, const std::string& line)>& row) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the " + what);
  std::string line;
  int lineno = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty() || line[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(lineno);
    if (!header_seen) {
      header_seen = true;
      if (line.rfind(header, 0) != 0) throw InputError(where, "", "expected a header starting with '" + header + "'");
      continue;
    }
    row(where, line);
  }
}

}  // namespace imcol
