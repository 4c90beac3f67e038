// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Wall-clock seconds for the run statistics (steady clock), and the calling thread's CPU time.
#include <chrono>
#include <ctime>

namespace imcol {

using WallClock = std::chrono::steady_clock;

inline double seconds_since(WallClock::time_point t0) {
  return std::chrono::duration<double>(WallClock::now() - t0).count();
}

/// CPU seconds the calling thread has used (user + system; CLOCK_THREAD_CPUTIME_ID).
inline double thread_cpu_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

}  // namespace imcol
