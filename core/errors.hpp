// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Error types shared by all modules. InputError -> exit status 2, SolverError -> exit status 3.
#include <sstream>
#include <stdexcept>
#include <string>

namespace imcol {

/// A number as messages write it (shortest default formatting).
inline std::string fmt_number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

/// Bad input: names the place (file[:line] or "--set"), the key and the problem, on one line
/// (control characters in any part are written as escapes such as \n).
class InputError : public std::runtime_error {
 public:
  InputError(std::string where, std::string key, const std::string& problem);
  const std::string& where() const { return where_; }
  const std::string& key() const { return key_; }

 private:
  std::string where_, key_;
};

/// The time integrator failed: what failed, when, and which state components were to blame.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace imcol
