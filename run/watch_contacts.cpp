// SPDX-License-Identifier: BSD-3-Clause
#include "run/watch_contacts.hpp"

#include "run/event_kind.hpp"

namespace imcol::run {


ContactLog::ContactLog(const model::CollisionModel& model) {
  if (model.started_in_contact()) contacts_.push_back({0.0, model.initial_u_rel(), std::nullopt, std::nullopt});
}

std::optional<model::Declared> ContactLog::on_event(const model::EventRecord& e) {
  if (kind_of(e) == EventKind::contact_in) {
    contacts_.push_back({e.t, e.u_rel, std::nullopt, std::nullopt});
  } else if (kind_of(e) == EventKind::contact_out && !contacts_.empty() && !contacts_.back().t_out) {
    contacts_.back().t_out = e.t;
    contacts_.back().u_out = e.u_rel;
  } else if ((kind_of(e) == EventKind::unload || kind_of(e) == EventKind::apex) && !t_together_) {
    t_together_ = e.t;
  }
  return std::nullopt;
}

}  // namespace imcol::run
