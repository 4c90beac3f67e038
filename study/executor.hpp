// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where a study's independent runs go, and how its caller follows and stops it. A study (study/) runs many scenes
// that do not depend on each other; it hands them to an Executor: this process's threads, or (apps/cluster.hpp) the
// ranks of an MPI job, which carry each result as bytes written from its type (nlohmann's to_json/from_json).
#include <cstddef>
#include <functional>
#include <string>

#include "core/work_scope.hpp"

namespace imcol::study {

/// What the caller of a study sees while it runs: progress(done, total) after each finished run, in one thread at a
/// time; cancelled() before each run is handed out: true hands out no further runs (those started finish) and the
/// study returns what finished, with its `cancelled` flag set. `stop` reaches the runs in flight too: each ends at its
/// next step (core/stop.hpp) and is dropped, and the study returns what finished, cancelled. Without `stop`, the stop
/// request of the calling thread's work (core/work_scope.hpp) does the same.
struct Hooks {
  std::function<void(std::size_t done, std::size_t total)> progress;
  std::function<bool()> cancelled;
  StopToken stop;
  bool cancel_requested() const { return stop.stop_requested() || (cancelled && cancelled()); }
};

/// The work control of a study's runs: the hooks' stop (else the calling thread's), no progress meter (a study
/// reports finished runs through Hooks::progress, not a run's simulated time).
inline WorkControl run_control(const Hooks& hooks) {
  return {hooks.stop.stop_possible() ? hooks.stop : this_thread_work().stop, nullptr};
}

/// The contract of apps/cluster.hpp's run_distributed: work(i) for every i < n on every process, each on `jobs`
/// threads; done(i, bytes, rank) on the deciding process (rank 0) alone, one call at a time; done returns false to
/// hand out no further runs.
using Distribute = std::function<void(std::size_t n, int jobs, const std::function<std::string(std::size_t)>& work,
                                      const std::function<bool(std::size_t, std::string, int)>& done)>;

struct Executor {
  int jobs = 0;           // threads of this process (0 = all cores), at most one per run
  Distribute distribute;  // empty: this process's threads alone (no bytes)
  std::function<void(std::string&)> share;  // makes the deciding process's bytes every process's; empty: one process
  int rank = 0, ranks = 1;
  /// This process decides and holds the results (rank 0). Other ranks run their share and get empty results.
  bool deciding() const { return rank == 0; }
};

/// This process's threads: `jobs` (0 = all cores).
inline Executor threads(int jobs = 0) {
  Executor e;
  e.jobs = jobs;
  return e;
}

}  // namespace imcol::study
