// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The shipped scenes (data/scenes/): each with the name `imcol run` takes, its kind (sphere-wall, sphere-sphere,
// free sphere, flow; "coupled" with the flow kernel) and its description.
#include <string>
#include <vector>

namespace imcol::study {

struct SceneEntry {
  std::string name, kind, description;
};

/// The shipped scenes matching `pattern` (a part of the name or description, case-insensitive, or a glob on the
/// name: `*`, `?`; "" for all), grouped by folder: the top level first, then each folder in order.
std::vector<SceneEntry> shipped_scenes(const std::string& pattern);

/// Their names, in the same order.
std::vector<std::string> matching_scenes(const std::string& pattern);

}  // namespace imcol::study
