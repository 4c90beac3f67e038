// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The stop token and progress meter of the work this thread is doing, installed for a scope: the caller of long work
// (the command line, the Python module, a study's worker threads) installs them; the run's loops (run/recorder.hpp,
// coupling/flow_coupling.hpp, run/flow_run.hpp) read them once when they start.
#include "core/progress_meter.hpp"
#include "core/stop.hpp"

namespace imcol {

struct WorkControl {
  StopToken stop;                    // never requested: run to the end
  ProgressMeter* meter = nullptr;    // none: report nothing
};

/// This thread's control (default: none), as the innermost WorkScope set it.
const WorkControl& this_thread_work();

/// Installs `control` as this thread's for its lifetime; restores the previous one after.
class WorkScope {
 public:
  explicit WorkScope(WorkControl control);
  ~WorkScope();
  WorkScope(const WorkScope&) = delete;
  WorkScope& operator=(const WorkScope&) = delete;

 private:
  WorkControl previous_;
};

}  // namespace imcol
