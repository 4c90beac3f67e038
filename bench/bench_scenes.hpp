// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Scenes shared by the Google Benchmark programs: a shipped scene, optionally with the history effect.
#include <string>
#include <vector>

#include "core/materials.hpp"
#include "core/scene.hpp"

namespace imcol::bench {

inline const char* kWallScene = "default.toml";  // steel onto Zerodur, 0.5 D gap, t_end 1 s
inline const char* kPairScene = "gg3462.toml";   // glass onto glass, t_end 0.06 s

/// The shipped scene `file` (data_dir()/scenes) with `extra` overrides; its effects with "history"
/// (modes > 0 fixes the number of exponentials, 0 keeps the tolerance) or without it (scenes
/// without an effects list have history on by default since 0.2.0).
inline Scene scene(const std::string& file, bool history, long modes = 0, std::vector<Override> extra = {}) {
  const std::string path = data_dir() + "/scenes/" + file;
  std::string list = "[";
  for (Effect e : load_scene(path).effects)
    if (e != Effect::history) list.append("\"").append(to_string(e)).append("\", ");
  extra.insert(extra.begin(), {"effects", list + (history ? "\"history\"]" : "]")});
  if (history && modes > 0) extra.push_back({"history.modes", std::to_string(modes)});
  return load_scene(path, extra);
}

}  // namespace imcol::bench
