// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Values between C++ and Python: JSON documents as Python objects, Python values as TOML value text.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace imcol::python {

/// A JSON value as Python: objects -> dict (keys in order), arrays -> list, null -> None.
pybind11::object to_python(const nlohmann::ordered_json& j);

/// A Python value as the text of a TOML value, as `--set key=TEXT` takes it: a str as it is (a bare word is a
/// string, TOML syntax such as "[1, 2]" or "\"x\"" is read as TOML); bool, int and float (round-trip digits) as
/// TOML; a list or tuple as a TOML array (its strings quoted).
std::string toml_value_text(const pybind11::handle& value);

/// The solver options of run() and sweep() as overrides of the solver keys, as --rtol / --atol / --integrator are.
std::vector<Override> solver_overrides(const std::optional<pybind11::object>& rtol,
                                       const std::optional<pybind11::object>& atol,
                                       const std::optional<std::string>& integrator);

}  // namespace imcol::python
