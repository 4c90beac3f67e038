// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Scenes by name: a scene argument that is not an existing path names a shipped scene, a file under
// data_dir()/scenes ("default", "coupled/gg3462", with or without ".toml").
#include <optional>
#include <string>
#include <vector>

namespace imcol {

/// The shipped scenes' folder: data_dir()/scenes.
std::string scenes_dir();

/// The file a scene argument stands for: `arg` itself if it exists (a path wins, but for a folder named as a shipped
/// scene: an output folder `default` leaves `default` the shipped scene); else the shipped scene of that name (".toml"
/// optional; a leading "data/scenes/" is dropped, so the README's paths work from any folder).
/// Throws InputError (key 'scene') saying where it looked, with the shipped scenes of a close name.
std::string find_scene(const std::string& arg);

/// The file a scene argument stands for, as find_scene finds it; nullopt when there is none.
std::optional<std::string> locate_scene(const std::string& arg);

/// Shipped scenes whose name (or its last part) is within a few edits of `name` (without ".toml"), or contains it;
/// closest first, at most five.
std::vector<std::string> close_scene_names(const std::string& name);

/// The shipped scenes' names, as find_scene takes them ("default", "coupled/gg3462"), sorted.
std::vector<std::string> shipped_scene_names();

}  // namespace imcol
