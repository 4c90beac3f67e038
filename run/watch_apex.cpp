// SPDX-License-Identifier: BSD-3-Clause
#include "run/watch_apex.hpp"

#include "run/event_kind.hpp"

namespace imcol::run {


void Apex::roots(std::vector<model::WatchedRoot>& out) const {
  if (model_.phase() == model::Phase::separated && !seen_)
    out.push_back({tag(EventKind::apex), "u_rel=0 (apex)", model::WatchedRoot::Of::u_rel, 0.0, +1, false});
}

std::optional<model::Declared> Apex::on_event(const model::EventRecord& e) {
  if (kind_of(e) == EventKind::contact_out) seen_ = false;
  if (kind_of(e) == EventKind::apex) seen_ = true;
  return std::nullopt;
}

}  // namespace imcol::run
