// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The value a numeric scene key has in a scene: where `imcol calibrate` starts its search.
#include <optional>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace imcol::study {

/// The value of `key` (as --set takes it) in `base`, the scene read from `scene_path` with `overrides`: the value
/// the reader resolved for the keys a Scene holds as they are (sphere[i] and wall properties with their materials
/// filled in, fluid.density/viscosity, contact.*), else the last override of the key or the file's value; none when
/// the scene leaves the key to a default the Scene does not hold as such.
std::optional<double> scene_value(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                                  const std::string& key);

}  // namespace imcol::study
