// SPDX-License-Identifier: BSD-3-Clause
#include "run/watch_instant.hpp"

#include "run/event_kind.hpp"

namespace imcol::run {

using model::WatchedRoot;

InstantSpeeds::InstantSpeeds(const model::CollisionModel& model, const Scene& sc) {
  const double D = 2 * model.radius(0);
  gap_ = sc.measure.instant_gap * D;
  all_ = sc.measure.bounces == BouncesMode::all;
  inside_ = model.has_target() && model.initial_gap() <= gap_;
  if (model.started_in_contact() && model.initial_gap() <= gap_) u_in_ = model.initial_u_rel();
}

void InstantSpeeds::roots(std::vector<WatchedRoot>& out) const {
  const WatchedRoot in{tag(EventKind::instant_in), "gap=instant_gap (in)", WatchedRoot::Of::gap, gap_, -1, true};
  const WatchedRoot outward{tag(EventKind::instant_out), "gap=instant_gap (out)", WatchedRoot::Of::gap, gap_, +1, true};
  if (all_) out.push_back(inside_ ? outward : in);
  else if (!u_in_) out.push_back(in);
  else if (!u_out_) out.push_back(outward);
}

std::optional<model::Declared> InstantSpeeds::on_event(const model::EventRecord& e) {
  if (kind_of(e) == EventKind::instant_in) {
    if (!u_in_) u_in_ = e.u_rel;
    inside_ = true;
    crossings_.push_back({e.t, e.u_rel, true});
  } else if (kind_of(e) == EventKind::instant_out) {
    if (!u_out_ && u_in_) u_out_ = e.u_rel;
    inside_ = false;
    crossings_.push_back({e.t, e.u_rel, false});
  }
  return std::nullopt;
}

}  // namespace imcol::run
