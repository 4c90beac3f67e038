// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A scene key that `imcol calibrate` fits: its bounds and scale (`--fit KEY=LO:HI[:log]`), and the map between the
// key's value and the optimiser's coordinate u in [0, 1] (linear, or linear in log10 of the value).
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace imcol::calib {

enum class Scale { linear, log };

struct FitParameter {
  std::string key;  // a numeric scene key, as --set takes it (e.g. contact.delta_ss, sphere[0].velocity)
  double lo = 0, hi = 0;  // bounds, in the key's SI units; lo < hi; both > 0 for a log scale
  Scale scale = Scale::linear;
};

/// Reads "KEY=LO:HI" or "KEY=LO:HI:log". Checks the bounds (finite, LO < HI, LO > 0 for log) and that KEY is a numeric
/// key of the scene `scene_path`: setting it to LO and to HI, after `overrides` (the --set ones), must give a valid
/// scene. Throws InputError("command line", "--fit", ...) naming the key and the problem.
FitParameter parse_fit_parameter(const std::string& text, const std::string& scene_path,
                                 const std::vector<Override>& overrides = {});

/// u in [0, 1] → the key's value, and back (clamped to [0, 1]).
double value_of(const FitParameter& p, double u);
double unit_of(const FitParameter& p, double value);

/// The overrides that set each parameter to its value (values[i] for params[i]), written so that they read back
/// to the same double.
std::vector<Override> overrides_for(const std::vector<FitParameter>& params, const std::vector<double>& values);

}  // namespace imcol::calib
