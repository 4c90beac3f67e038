// SPDX-License-Identifier: BSD-3-Clause
#include "calibrate/fit_parameter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/number_text.hpp"
#include "core/errors.hpp"

namespace imcol::calib {

namespace {

[[noreturn]] void fail(const std::string& key, const std::string& problem) {
  throw InputError("command line", "--fit", key.empty() ? problem : "parameter '" + key + "': " + problem);
}

/// A bound: a finite number, the whole text.
double bound(const std::string& key, const std::string& text, const char* which) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) fail(key, std::string(which) + " bound '" + text + "' is not a number");
  if (!std::isfinite(v)) fail(key, std::string(which) + " bound '" + text + "' is not finite");
  return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out(1);
  for (char c : s) {
    if (c == sep) out.emplace_back();
    else out.back() += c;
  }
  return out;
}


}  // namespace

FitParameter parse_fit_parameter(const std::string& text, const std::string& scene_path, const std::vector<Override>& overrides) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) fail("", "expected KEY=LO:HI or KEY=LO:HI:log, got '" + text + "'");
  FitParameter p;
  p.key = text.substr(0, eq);
  const auto parts = split(text.substr(eq + 1), ':');
  if (parts.size() < 2 || parts.size() > 3) fail(p.key, "expected LO:HI or LO:HI:log after '=', got '" + text.substr(eq + 1) + "'");
  p.lo = bound(p.key, parts[0], "lower");
  p.hi = bound(p.key, parts[1], "upper");
  if (parts.size() == 3) {
    if (parts[2] != "log") fail(p.key, "unknown scale '" + parts[2] + "' (expected log, or nothing for a linear scale)");
    p.scale = Scale::log;
  }
  if (!(p.lo < p.hi)) fail(p.key, "bounds reversed or empty: LO = " + fmt_number(p.lo) + " is not below HI = " + fmt_number(p.hi));
  if (p.scale == Scale::log && p.lo <= 0) fail(p.key, "a log scale needs LO > 0, got " + fmt_number(p.lo));
  // A numeric key: the scene reader takes it at both bounds (an unknown key, a string or integer key, or a bound the
  // scene refuses fails here).
  for (double v : {p.lo, p.hi}) {
    std::vector<Override> ov = overrides;
    ov.push_back({p.key, toml_float(v)});
    try {
      (void)load_scene(scene_path, ov);
    } catch (const InputError& e) {
      // The scene reader refuses a fractional value of an integer key: no value of the search would do.
      if (e.key() == p.key && e.problem() == "must be an integer")
        fail(p.key, "integer keys cannot be fitted (" + p.key + " is an integer; fit only keys that take any number)");
      fail(p.key, "the scene refuses " + p.key + " = " + fmt_number(v) + " (fit only numeric keys, within the scene's limits): " + e.problem());
    }
  }
  return p;
}

double value_of(const FitParameter& p, double u) {
  if (!(u > 0)) return p.lo;  // also NaN
  if (u >= 1) return p.hi;
  if (p.scale == Scale::log) return std::pow(10.0, std::log10(p.lo) + u * (std::log10(p.hi) - std::log10(p.lo)));
  return p.lo + u * (p.hi - p.lo);
}

double unit_of(const FitParameter& p, double value) {
  const double u = p.scale == Scale::log
                       ? (value > 0 ? (std::log10(value) - std::log10(p.lo)) / (std::log10(p.hi) - std::log10(p.lo)) : 0.0)
                       : (value - p.lo) / (p.hi - p.lo);
  return std::isnan(u) ? 0.0 : std::clamp(u, 0.0, 1.0);
}

std::vector<Override> overrides_for(const std::vector<FitParameter>& params, const std::vector<double>& values) {
  std::vector<Override> ov;
  for (std::size_t i = 0; i < params.size() && i < values.size(); ++i) ov.push_back({params[i].key, toml_float(values[i])});
  return ov;
}

}  // namespace imcol::calib
