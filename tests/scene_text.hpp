// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Scene-file text for the tests: one builder per TOML table, so that fixtures are not copied around.
#include <gtest/gtest.h>

#include <string>

#include "core/number_text.hpp"

namespace imcol::test {

/// Shortest round-trip form, with ".0" on whole numbers so that TOML reads a float.
inline std::string num(double v) { return toml_float(v); }

inline std::string fluid(double viscosity, double density = 1000.0) {
  return "[fluid]\ndensity = " + num(density) + "\nviscosity = " + num(viscosity) + "\n";
}

inline std::string sphere(const std::string& material, double diameter, double position, double velocity) {
  return "[[sphere]]\nmaterial = \"" + material + "\"\ndiameter = " + num(diameter) + "\nposition = " + num(position) +
         "\nvelocity = " + num(velocity) + "\n";
}

inline std::string wall(const std::string& material, double position) {
  return "[wall]\nmaterial = \"" + material + "\"\nposition = " + num(position) + "\n";
}

/// The common wall scene of the input tests: lines 2-3 fluid, 4-8 sphere, 9-11 wall.
inline std::string basic_wall_scene() { return fluid(0.01) + sphere("steel", 0.0127, -0.02, 0.2) + wall("glass", 0.0); }

/// `text` with the first `from` replaced by `to` (a test failure if `from` is absent).
inline std::string edit(std::string text, const std::string& from, const std::string& to) {
  const auto p = text.find(from);
  if (p == std::string::npos) {
    ADD_FAILURE() << "'" << from << "' not in the scene text";
    return text;
  }
  return text.replace(p, from.size(), to);
}

}  // namespace imcol::test
