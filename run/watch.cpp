// SPDX-License-Identifier: BSD-3-Clause
#include "run/watch.hpp"

namespace imcol::run {

Watch::Watch(model::CollisionModel& model, const Scene& sc)
    : stalled_approach(model, sc), apex(model), instant(model, sc), first_bounce(model, sc, instant), rest(model, sc),
      slow_contact(model, sc, rest), contacts(model) {
  const bool all = sc.measure.bounces == BouncesMode::all;
  model.watch(stalled_approach);
  if (all) model.watch(apex);
  if (!all) model.watch(first_bounce);
  model.watch(instant);
  model.watch(rest);
  if (all) model.watch(slow_contact);
  model.watch(contacts);
}

}  // namespace imcol::run
