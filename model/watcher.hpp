// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The seam between the model's events and the rules that measure a run or end it (those live in run/). The model
// signals its events by kind; a watcher asks for extra roots (a level of the gap or of U_rel, crossed in a direction),
// hears every event and every output sample, says until when its rule lets the run go on, and may declare a state
// (at rest) that the model records as an event. The model stops at the earliest of its watchers' stop times.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "model/event.hpp"

namespace imcol::model {

struct Evaluation;

/// A root a watcher wants armed: g = (gap or U_rel) − level crossing zero in `direction` (+1 rising, −1 falling, 0 both).
struct WatchedRoot {
  enum class Of { gap, u_rel };
  EventTag kind;      // the watcher's kind (run/event_kind.hpp)
  std::string name;   // the event's name in events() (summary.json's `events`)
  Of of;
  double level;       // m for the gap, m/s for U_rel
  int direction;
  bool restarts;      // the event re-arms the roots and restarts the integrator (false: diagnostic)
};

/// A state a watcher declares (e.g. at rest), recorded by the model as an event at the present gap and U_rel.
struct Declared {
  EventTag kind;
  std::string name;
};

class EventWatcher {
 public:
  virtual ~EventWatcher() = default;
  /// Appends the roots this watcher wants armed now (asked whenever the model arms its roots, in the watchers' order,
  /// after the model's contact roots and before its lubrication and blend roots).
  virtual void roots(std::vector<WatchedRoot>& out) const { (void)out; }
  /// An event, after the model has handled it (its phase, contacts and contact times are the new ones).
  virtual std::optional<Declared> on_event(const EventRecord& e) { (void)e; return std::nullopt; }
  /// Whether on_sample reads the sample's forces and accelerations now (otherwise the sample may be kinematic).
  virtual bool wants_forces() const { return false; }
  /// An output sample (a row of the trajectory).
  virtual std::optional<Declared> on_sample(double t, const Evaluation& ev) { (void)t; (void)ev; return std::nullopt; }
  /// The latest time this watcher's rule lets the run go on to, s (+inf: no limit).
  virtual double stop_time() const { return std::numeric_limits<double>::infinity(); }
};

}  // namespace imcol::model
