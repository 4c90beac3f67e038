// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What an event is, by name: the model's roots (model/event.hpp ModelRoot, same tags) and the kinds of the watchers'
// roots and declared states (run/watch_*.hpp).
#include "model/event.hpp"

namespace imcol::run {

using model::ModelRoot;

enum class EventKind : model::EventTag {
  contact_in = model::tag(ModelRoot::contact_in),
  contact_out = model::tag(ModelRoot::contact_out),
  unload = model::tag(ModelRoot::unload),
  touch = model::tag(ModelRoot::touch),
  lub_edge = model::tag(ModelRoot::lub_edge),
  blend_edge = model::tag(ModelRoot::blend_edge),
  blend_end = model::tag(ModelRoot::blend_end),
  start_in_contact = model::tag(ModelRoot::start_in_contact),
  // the watchers'
  instant_in = model::kFirstWatcherTag,
  instant_out,
  closest,
  apex,
  rebound_stalled,
  measure_out,
  at_rest,
};

constexpr model::EventTag tag(EventKind k) { return static_cast<model::EventTag>(k); }
constexpr EventKind kind_of(const model::EventRecord& e) { return static_cast<EventKind>(e.kind); }

}  // namespace imcol::run
