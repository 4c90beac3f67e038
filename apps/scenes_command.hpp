// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol scenes [PATTERN]`: the shipped scenes (data/scenes/), grouped by folder, each with the name `imcol run`
// takes, its kind (sphere-wall, sphere-sphere, free sphere, flow; "coupled" with the flow kernel) and its description.
#include <string>
#include <vector>

#include "study/scene_catalog.hpp"

namespace imcol {

/// PATTERN: a part of the name or description (case-insensitive), or a glob on the name (`*`, `?`); "" lists all.
int cmd_scenes(const std::string& pattern);

/// The names of the shipped scenes `imcol scenes PATTERN` lists, in its order (grouped by folder).
using study::matching_scenes;

}  // namespace imcol
