// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// e_instant (docs/bounces.md): U_rel at the first inward crossing of measure.instant_gap and at the next outward one
// (either side of δ_SS). With measure.bounces = "all" every crossing is an event, alternately inward and outward.
#include <optional>

#include "core/scene.hpp"
#include "model/collision_model.hpp"

namespace imcol::run {

/// A crossing of measure.instant_gap: time (s), U_rel (m/s) and whether inward.
struct Crossing {
  double t, u;
  bool in;
};

class InstantSpeeds : public model::EventWatcher {
 public:
  InstantSpeeds(const model::CollisionModel& model, const Scene& sc);
  void roots(std::vector<model::WatchedRoot>& out) const override;
  std::optional<model::Declared> on_event(const model::EventRecord& e) override;
  /// U_rel at the first inward crossing (the initial one for a start inside the contact zone below instant_gap) and at
  /// the next outward crossing, m/s.
  std::optional<double> u_in() const { return u_in_; }
  std::optional<double> u_out() const { return u_out_; }
  /// Every crossing that was an event, in order.
  const std::vector<Crossing>& crossings() const { return crossings_; }

 private:
  double gap_;    // measure.instant_gap, m
  bool all_;      // measure.bounces = "all"
  bool inside_;   // all bounces: inside instant_gap (the next root is outward)
  std::optional<double> u_in_, u_out_;
  std::vector<Crossing> crossings_;
};

}  // namespace imcol::run
