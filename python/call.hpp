// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Bad input raised in Python's words: a ValueError that names the Python call (imcol.sweep, Scene.set('key')) and the
// key, instead of the command line's place (--set, command line); a scene file's place (file:line) is kept after it.
#include <pybind11/pybind11.h>

#include <string>
#include <utility>

#include "core/errors.hpp"

namespace imcol::python {

/// The message of the ValueError `call` raises for `e`: "CALL: key 'K': problem" for a value given to the call (an
/// override, an argument; the key left out when `call` names it already), "CALL: FILE:LINE: key 'K': problem" for a
/// scene file's line.
std::string call_message(const std::string& call, const InputError& e);

/// `f` bound as the module's function `call`: the same arguments; bad input (InputError) raises ValueError with
/// call_message.
template <class R, class... A>
auto in_call(const char* call, R (*f)(A...)) {
  return [call, f](A... args) -> R {
    try {
      return f(std::forward<A>(args)...);
    } catch (const InputError& e) {
      throw pybind11::value_error(call_message(call, e));
    }
  };
}

}  // namespace imcol::python
