// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Wall-clock seconds for the run statistics (steady clock).
#include <chrono>

namespace imcol {

using WallClock = std::chrono::steady_clock;

inline double seconds_since(WallClock::time_point t0) {
  return std::chrono::duration<double>(WallClock::now() - t0).count();
}

}  // namespace imcol
