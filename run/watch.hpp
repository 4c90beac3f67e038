// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The rules that measure a run or end it, each a watcher of the model's events (model/watcher.hpp) in its own file,
// added to the model before it is integrated. Their order is the order of their roots.
#include "core/scene.hpp"
#include "model/collision_model.hpp"
#include "run/watch_apex.hpp"
#include "run/watch_contacts.hpp"
#include "run/watch_first_bounce.hpp"
#include "run/watch_instant.hpp"
#include "run/watch_rest.hpp"
#include "run/watch_slow_contact.hpp"
#include "run/watch_stalled_approach.hpp"

namespace imcol::run {

class Watch {
 public:
  /// Builds the scene's watchers and adds them to `model`, which must not outlive them (nor be integrated after them).
  /// Not a const object: the model updates the watchers as it runs.
  Watch(model::CollisionModel& model, const Scene& sc);
  Watch(const Watch&) = delete;
  Watch& operator=(const Watch&) = delete;

  StalledApproach stalled_approach;
  Apex apex;
  InstantSpeeds instant;
  FirstBounceStop first_bounce;
  RestDetection rest;
  SlowContactRest slow_contact;
  ContactLog contacts;
};

}  // namespace imcol::run
