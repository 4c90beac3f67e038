// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Independent runs on a few threads (the studies): each run apart, its result taken in under one lock.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <mutex>
#include <thread>
#include <vector>

#include "core/work_scope.hpp"

namespace imcol::study {

/// The threads for n runs: `requested` (0 = all cores), at most n.
inline int job_count(int requested, std::size_t n) {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<int>(std::min<std::size_t>(n, requested > 0 ? static_cast<std::size_t>(requested) : hw));
}

/// Runs work(i) for i in [0, n) on `jobs` threads, in order of i; as each finishes, done(i, result) in one thread at
/// a time. done returns false to hand out no further runs (those started still finish). The threads work under the
/// calling thread's stop request (core/work_scope.hpp, no progress meter); a work(i) that throws Interrupted hands out
/// no further runs, and once the others ended, Interrupted is thrown here.
template <class Work, class Done>
void run_parallel(std::size_t n, int jobs, Work work, Done done) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> interrupted{false};
  std::mutex mu;
  const StopToken stop = this_thread_work().stop;
  auto worker = [&] {
    WorkScope scope({stop, nullptr});
    try {
      for (std::size_t i = next++; i < n; i = next++) {
        auto result = work(i);
        std::lock_guard lock(mu);
        if (!done(i, std::move(result))) next = n;
      }
    } catch (const Interrupted&) {
      interrupted = true;
      next = n;
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < jobs; ++j) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  if (interrupted) throw Interrupted{};
}

}  // namespace imcol::study
