// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An approach stopped without contact (MODEL.md §3): U_rel falls to measure.stall_fraction × the initial approach speed
// before the gap reaches δ_SS. The run ends one measure.window later (the rebound fit's window), unless a contact
// follows after all.
#include <limits>
#include <optional>

#include "core/scene.hpp"
#include "model/collision_model.hpp"

namespace imcol::run {

class StalledApproach : public model::EventWatcher {
 public:
  StalledApproach(const model::CollisionModel& model, const Scene& sc);
  void roots(std::vector<model::WatchedRoot>& out) const override;
  std::optional<model::Declared> on_event(const model::EventRecord& e) override;
  double stop_time() const override { return stop_; }
  /// When the approach stopped, s (none after a contact before it).
  std::optional<double> t_closest() const { return t_closest_; }

 private:
  const model::CollisionModel& model_;
  double speed_;   // U_rel below which the approach counts as stopped, m/s
  double window_;  // s
  std::optional<double> t_closest_;
  double stop_ = std::numeric_limits<double>::infinity();
};

}  // namespace imcol::run
