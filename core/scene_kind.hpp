// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Which reader a scene file is for, told by its top-level keys: a collision scene (imcol run, sweep, ...;
// core/scene.hpp) or a flow scene (imcol flow; flow/flow_scene.hpp). Each reader refuses the other kind by
// naming the command that takes it, rather than a key it misses.
#include <toml++/toml.h>

#include <string>

namespace imcol {

enum class SceneKind { collision, flow, unclear };

/// `collision` when the file has a key only collision scenes have and none only flow scenes have; `flow` the other
/// way round; else `unclear` (the reader's own messages then say what is wrong).
inline SceneKind scene_kind(const toml::table& root) {
  bool collision = false, flow = false;
  for (const char* k : {"effects", "solver", "contact", "measure", "drag", "lubrication", "added_mass", "history", "gravity"})
    collision = collision || root.contains(k);
  for (const char* k : {"grid", "time", "stream"}) flow = flow || root.contains(k);
  return collision == flow ? SceneKind::unclear : collision ? SceneKind::collision : SceneKind::flow;
}

/// The message for a scene of kind `kind` given to the other kind's command.
inline std::string other_scene_kind_message(SceneKind kind) {
  return kind == SceneKind::flow
             ? "this is a flow scene ([grid], [time] or [stream], none of a collision scene's keys): run it with `imcol flow`"
             : "this is a collision scene (effects, [solver], [contact] or another collision key; no [grid], [time] or [stream]): "
               "run it with `imcol run` (or sweep, bench and the other collision commands)";
}

}  // namespace imcol
