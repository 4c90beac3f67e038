// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The first rebound (measure.bounces = "first", docs/bounces.md): after the first separation the run goes on until the
// rebound has passed the gaps its measures read (max(at_gap, δ_SS + fit_distance) outward and, after an inward
// crossing, measure.instant_gap outward) or has stalled (U_rel above −stall_fraction × the impact speed), and at least
// one measure.window past the separation (or to t_end).
#include <limits>
#include <optional>

#include "core/scene.hpp"
#include "model/collision_model.hpp"
#include "run/watch_instant.hpp"

namespace imcol::run {

class FirstBounceStop : public model::EventWatcher {
 public:
  FirstBounceStop(const model::CollisionModel& model, const Scene& sc, const InstantSpeeds& instant);
  void roots(std::vector<model::WatchedRoot>& out) const override;
  std::optional<model::Declared> on_event(const model::EventRecord& e) override;
  double stop_time() const override { return stop_; }

 private:
  /// Sets the stop time once the rebound's measurements are complete (or can no longer be).
  void check(double t);

  const model::CollisionModel& model_;
  const InstantSpeeds& instant_;
  double gap_;             // max(at_gap, δ_SS + fit_distance), m
  double stall_fraction_;
  double window_;          // s
  bool separated_ = false, gap_passed_ = false, stalled_ = false;
  bool instant_out_ = false;  // the outward instant crossing (heard here: InstantSpeeds may hear it after this watcher)
  double stop_ = std::numeric_limits<double>::infinity();
};

}  // namespace imcol::run
