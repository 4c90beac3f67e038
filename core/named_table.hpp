// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A table of entries by name (the materials, the fluids): lookup and the list of names for error messages.
#include <map>
#include <string>

namespace imcol {

template <class Entry>
class NamedTable {
 public:
  const Entry* find(const std::string& name) const {
    auto it = by_name_.find(name);
    return it == by_name_.end() ? nullptr : &it->second;
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

}  // namespace imcol
