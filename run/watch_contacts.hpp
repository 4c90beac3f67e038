// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The contacts of a run as the measures read them (docs/bounces.md): each contact's inward δ_SS crossing (or the start
// inside the contact zone) and its separation, with U_rel there; and when the pair first moved together (the first
// U_rel = 0 in contact or at an apex).
#include <optional>
#include <vector>

#include "model/collision_model.hpp"

namespace imcol::run {

/// One contact: the inward δ_SS crossing and the separation (outward crossing), s and m/s (U_rel > 0 approaching).
struct Contact {
  double t_in, u_in;
  std::optional<double> t_out, u_out;
};

class ContactLog : public model::EventWatcher {
 public:
  explicit ContactLog(const model::CollisionModel& model);
  std::optional<model::Declared> on_event(const model::EventRecord& e) override;
  /// In order; a start inside the contact zone is the first, at t = 0 with the initial U_rel.
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// The first loading -> unloading switch or apex, s: where the relative velocity first vanished.
  std::optional<double> t_together() const { return t_together_; }

 private:
  std::vector<Contact> contacts_;
  std::optional<double> t_together_;
};

}  // namespace imcol::run
