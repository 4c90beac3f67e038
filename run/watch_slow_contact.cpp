// SPDX-License-Identifier: BSD-3-Clause
#include "run/watch_slow_contact.hpp"

#include "run/event_kind.hpp"

#include <cmath>

namespace imcol::run {

std::optional<model::Declared> SlowContactRest::on_event(const model::EventRecord& e) {
  if (kind_of(e) != EventKind::contact_in || model_.contacts() <= 1) return std::nullopt;
  if (!(e.u_rel < stall_fraction_ * std::abs(model_.impact_speed()))) return std::nullopt;
  rest_.declare(e.t);
  return model::Declared{tag(EventKind::at_rest), "at rest (impact speed below stall_fraction x the first impact speed)"};
}

}  // namespace imcol::run
