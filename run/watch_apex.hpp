// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The apex of each flight between contacts (measure.bounces = "all"): the first U_rel = 0 after a separation, an event
// in the summary; the pair moves together there when it never separates again.
#include "model/collision_model.hpp"

namespace imcol::run {

class Apex : public model::EventWatcher {
 public:
  explicit Apex(const model::CollisionModel& model) : model_(model) {}
  void roots(std::vector<model::WatchedRoot>& out) const override;
  std::optional<model::Declared> on_event(const model::EventRecord& e) override;

 private:
  const model::CollisionModel& model_;
  bool seen_ = false;  // since the last separation
};

}  // namespace imcol::run
