// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Checks of command-line option values, attached to the options as CLI11 validators: a value that is not a number,
// not finite, outside its interval or not one of the choices is an InputError naming the option (exit 2, one line)
// while the command line is parsed, before anything runs. Vector options are checked element by element.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/choices.hpp"
#include "core/errors.hpp"
#include "core/scene_files.hpp"

namespace imcol {

/// Allowed values of a real option: [lo, hi] with the ends open as stated.
struct Interval {
  double lo, hi;
  bool lo_open = false, hi_open = false;
  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
  std::string text() const {
    return std::string(lo_open ? "(" : "[") + fmt_number(lo) + ", " + fmt_number(hi) + (hi_open ? ")" : "]");
  }
};

[[noreturn]] inline void bad_option(const std::string& option, const std::string& problem) {
  throw InputError("command line", option, problem);
}

/// A real number in `in` (and, as every scene number, 0 or of magnitude at least 1e-30).
inline CLI::Validator number_rule(const std::string& option, Interval in) {
  return CLI::Validator(
      [option, in](std::string& text) -> std::string {
        const char* s = text.c_str();
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(s, &end);
        if (text.empty() || end == s || *end != '\0' || std::isspace(static_cast<unsigned char>(text[0])))
          bad_option(option, "must be a number (got '" + text + "')");
        if (!std::isfinite(v)) bad_option(option, "must be a finite number (got " + text + ")");
        if (!in.contains(v)) bad_option(option, "must be in " + in.text() + " (got " + text + ")");
        if (v != 0 && std::abs(v) < 1e-30) bad_option(option, "must be 0 or of magnitude at least 1e-30 (got " + text + ")");
        return {};
      },
      "in " + in.text());
}

/// An integer (decimal digits, optional sign) in [lo, hi].
inline CLI::Validator integer_rule(const std::string& option, long lo, long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [option, lo, hi, range](std::string& text) -> std::string {
        const char* s = text.c_str();
        char* end = nullptr;
        errno = 0;
        const long v = std::strtol(s, &end, 10);
        if (text.empty() || end == s || *end != '\0' || std::isspace(static_cast<unsigned char>(text[0])))
          bad_option(option, "must be an integer (got '" + text + "')");
        if (errno == ERANGE || v < lo || v > hi) bad_option(option, "must be in " + range + " (got " + text + ")");
        return {};
      },
      "in " + range);
}

/// "a, b, c": the names for a message.
inline std::string name_list(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

/// One of `names`.
inline CLI::Validator choice_rule(const std::string& option, const std::vector<std::string>& names) {
  const std::string list = name_list(names);
  return CLI::Validator(
      [option, names, list](std::string& text) -> std::string {
        for (const auto& n : names)
          if (text == n) return {};
        bad_option(option, "unknown value '" + text + "' (expected " + list + ")");
      },
      "one of " + list);
}

/// A path (--out): not empty (an empty path would silently mean the default).
inline CLI::Validator path_rule(const std::string& option) {
  return CLI::Validator(
      [option](std::string& text) -> std::string {
        if (text.empty()) bad_option(option, "must not be empty (leave the option out for the default)");
        return {};
      },
      "");
}

/// A scene argument: an existing path, or a shipped scene's name (core/scene_files.hpp), replaced by the file it names.
inline CLI::Validator scene_rule() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        text = find_scene(text);
        return {};
      },
      "");
}

}  // namespace imcol
