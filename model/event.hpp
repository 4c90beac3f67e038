// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A discrete event of a run (MODEL.md §3), as the model records it for the summary. Its kind is a tag: the roots the
// model arms itself (ModelRoot) and the kinds of the watchers' roots (run/event_kind.hpp) share one numbering.
#include <cstdint>
#include <string>

namespace imcol::model {

using EventTag = std::uint8_t;

/// The roots the model arms (MODEL.md §3), and the state it declares itself (a start inside the contact zone).
enum class ModelRoot : EventTag { contact_in, contact_out, unload, touch, lub_edge, blend_edge, blend_end, start_in_contact };

/// The first tag free for the watchers' kinds.
inline constexpr EventTag kFirstWatcherTag = 16;

constexpr EventTag tag(ModelRoot r) { return static_cast<EventTag>(r); }

struct EventRecord {
  double t;
  std::string name;
  double gap;
  double u_rel;
  EventTag kind;  // a ModelRoot, or a watcher's kind
};

}  // namespace imcol::model
