// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// All bounces (measure.bounces = "all", docs/bounces.md): a contact slower than measure.stall_fraction × the first
// impact speed means the pair is at rest; the run ends there.
#include "core/scene.hpp"
#include "model/collision_model.hpp"
#include "run/watch_rest.hpp"

namespace imcol::run {

class SlowContactRest : public model::EventWatcher {
 public:
  SlowContactRest(const model::CollisionModel& model, const Scene& sc, RestDetection& rest)
      : model_(model), rest_(rest), stall_fraction_(sc.measure.stall_fraction) {}
  std::optional<model::Declared> on_event(const model::EventRecord& e) override;

 private:
  const model::CollisionModel& model_;
  RestDetection& rest_;  // keeps the verdict (RestDetection::since)
  double stall_fraction_;
};

}  // namespace imcol::run
