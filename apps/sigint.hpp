// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Ctrl-C for a command: while a SigintStop lives, SIGINT requests the stop of the work it controls (core/stop.hpp) and
// restores the default action, so that a second Ctrl-C ends the process at once. The work ends at its next step
// (Interrupted), its output folder is not committed (apps/output_unit.hpp) and the command exits 130.
#include "core/stop.hpp"

namespace imcol {

class SigintStop {
 public:
  SigintStop();   // installs the handler
  ~SigintStop();  // restores the previous action
  SigintStop(const SigintStop&) = delete;
  SigintStop& operator=(const SigintStop&) = delete;

  StopToken token() const { return source_.token(); }
  bool requested() const { return source_.stop_requested(); }

 private:
  StopSource source_;
};

/// The exit status of an interrupted command (128 + SIGINT, as a shell reports it).
constexpr int kInterruptedExit = 130;

}  // namespace imcol
