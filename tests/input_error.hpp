// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The message of the input error a call throws, for tests that check what it names.
#include <string>

#include "core/errors.hpp"

namespace imcol::test {

/// The message of the InputError `f()` throws; "" if it throws none.
template <class F>
std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace imcol::test
