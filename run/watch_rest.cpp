// SPDX-License-Identifier: BSD-3-Clause
#include "run/watch_rest.hpp"

#include "run/event_kind.hpp"

#include <algorithm>
#include <cmath>

namespace imcol::run {

using model::Phase;

RestDetection::RestDetection(const model::CollisionModel& model, const Scene& sc)
    : model_(model), all_(sc.measure.bounces == BouncesMode::all), stall_fraction_(sc.measure.stall_fraction), window_(sc.measure.window) {}

bool RestDetection::wants_forces() const {
  const Phase p = model_.phase();
  const bool watched = p == Phase::unloading || (all_ && p == Phase::separated);
  return !at_rest_ && model_.has_target() && watched;
}

std::optional<model::Declared> RestDetection::on_sample(double t, const model::Evaluation& ev) {
  if (!wants_forces()) {
    if (!at_rest_) quiet_since_.reset();
    return std::nullopt;
  }
  const double s = stall_fraction_ * std::max(std::abs(model_.impact_speed()), std::abs(model_.initial_u_rel()));
  const double a_rel = ev.f[0].accel - (model_.n_spheres() > 1 ? ev.f[1].accel : 0.0);
  if (!(std::abs(ev.u_rel) < s && std::abs(a_rel) * window_ < s)) {
    quiet_since_.reset();
    return std::nullopt;
  }
  if (!quiet_since_) quiet_since_ = t;
  if (t - *quiet_since_ < window_ * (1 - 1e-9)) return std::nullopt;
  at_rest_ = true;
  stop_ = std::min(stop_, t);
  return model::Declared{tag(EventKind::at_rest),
                         "at rest (|U_rel| and |dU_rel/dt| window below stall_fraction x impact speed for one window)"};
}

void RestDetection::declare(double t) {
  at_rest_ = true;
  quiet_since_ = t;
  stop_ = std::min(stop_, t);
}

}  // namespace imcol::run
