// SPDX-License-Identifier: BSD-3-Clause
#include "run/watch_first_bounce.hpp"

#include "run/event_kind.hpp"

#include <algorithm>
#include <cmath>

namespace imcol::run {

using model::WatchedRoot;

FirstBounceStop::FirstBounceStop(const model::CollisionModel& model, const Scene& sc, const InstantSpeeds& instant)
    : model_(model), instant_(instant), stall_fraction_(sc.measure.stall_fraction), window_(sc.measure.window) {
  const double D = 2 * model.radius(0);
  gap_ = std::max(sc.measure.at_gap * D, model.delta_ss_m() + sc.measure.fit_distance * D);
}

void FirstBounceStop::roots(std::vector<WatchedRoot>& out) const {
  if (model_.phase() != model::Phase::separated) return;
  if (!gap_passed_) out.push_back({tag(EventKind::measure_out), "gap=max(at_gap, delta_ss+fit_distance) (out)", WatchedRoot::Of::gap, gap_, +1, false});
  if (!stalled_)
    out.push_back({tag(EventKind::rebound_stalled), "u_rel=-stall_fraction*U_c (rebound stalled)", WatchedRoot::Of::u_rel,
                   -(stall_fraction_ * std::abs(model_.impact_speed())), +1, false});
}

std::optional<model::Declared> FirstBounceStop::on_event(const model::EventRecord& e) {
  switch (kind_of(e)) {
    case EventKind::contact_out:
      if (separated_) return std::nullopt;
      separated_ = true;
      if (e.u_rel > -stall_fraction_ * std::abs(model_.impact_speed())) stalled_ = true;
      break;
    case EventKind::instant_out: instant_out_ = true; break;
    case EventKind::measure_out: gap_passed_ = true; break;
    case EventKind::rebound_stalled: stalled_ = true; break;
    default: return std::nullopt;
  }
  check(e.t);
  return std::nullopt;
}

void FirstBounceStop::check(double t) {
  if (!model_.t_separation()) return;
  const bool pending = (instant_.u_in() && !instant_out_) || !gap_passed_;
  if (pending && !stalled_) return;
  stop_ = std::max(t, *model_.t_separation() + window_);
}

}  // namespace imcol::run
