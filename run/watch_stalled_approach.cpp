// SPDX-License-Identifier: BSD-3-Clause
#include "run/watch_stalled_approach.hpp"

#include "run/event_kind.hpp"

#include <algorithm>

namespace imcol::run {

using model::Phase;

StalledApproach::StalledApproach(const model::CollisionModel& model, const Scene& sc)
    : model_(model), speed_(sc.measure.stall_fraction * std::max(0.0, model.initial_u_rel())), window_(sc.measure.window) {}

void StalledApproach::roots(std::vector<model::WatchedRoot>& out) const {
  const Phase p = model_.phase();
  if ((p == Phase::approach || p == Phase::separated) && !model_.t_contact() && !t_closest_)
    out.push_back({tag(EventKind::closest), "u_rel=stall_fraction*U_rel0 (approach stopped)", model::WatchedRoot::Of::u_rel, speed_, -1, true});
}

std::optional<model::Declared> StalledApproach::on_event(const model::EventRecord& e) {
  if (kind_of(e) == EventKind::closest) {
    t_closest_ = e.t;
    stop_ = e.t + window_;
  } else if (kind_of(e) == EventKind::contact_in && t_closest_ && !model_.t_separation()) {
    stop_ = std::numeric_limits<double>::infinity();  // a contact after all
  }
  return std::nullopt;
}

}  // namespace imcol::run
