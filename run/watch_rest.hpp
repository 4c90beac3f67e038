// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// At rest (docs/bounces.md): after the first U_rel = 0 in contact (unloading, not separated; with measure.bounces =
// "all" also in flight after a contact), a pair with |U_rel| < s and |dU_rel/dt|·window < s, s = measure.stall_fraction
// × the impact speed, throughout one measure.window is at rest on the wall or moving with its partner: the run ends there
// (a longer run cannot change e = 0, and a stiff contact would otherwise be integrated to t_end at minute steps).
#include <limits>
#include <optional>

#include "core/scene.hpp"
#include "model/collision_model.hpp"

namespace imcol::run {

class RestDetection : public model::EventWatcher {
 public:
  RestDetection(const model::CollisionModel& model, const Scene& sc);
  bool wants_forces() const override;
  std::optional<model::Declared> on_sample(double t, const model::Evaluation& ev) override;
  double stop_time() const override { return stop_; }
  /// At rest from t on by another rule (the run ends at t).
  void declare(double t);
  /// The start of the quiet window that ended the run at rest, s (none if it did not).
  std::optional<double> since() const { return at_rest_ ? quiet_since_ : std::nullopt; }

 private:
  const model::CollisionModel& model_;
  bool all_;  // measure.bounces = "all": also in flight
  double stall_fraction_, window_;
  std::optional<double> quiet_since_;  // start of the current quiet stretch
  bool at_rest_ = false;
  double stop_ = std::numeric_limits<double>::infinity();
};

}  // namespace imcol::run
