// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How far long work has come: (done, total) in the work's own measure (simulated s of t_end for a run, finished runs
// of all for a study), set by the working thread and read by another (relaxed atomics: a reading may pair a new
// `done` with an old `total` for one poll, never a torn number).
#include <atomic>
#include <utility>

namespace imcol {

class ProgressMeter {
 public:
  void set(double done, double total) {
    total_.store(total, std::memory_order_relaxed);
    done_.store(done, std::memory_order_relaxed);
  }
  /// (done, total); total 0: nothing reported yet.
  std::pair<double, double> read() const { return {done_.load(std::memory_order_relaxed), total_.load(std::memory_order_relaxed)}; }

 private:
  std::atomic<double> done_{0}, total_{0};
};

}  // namespace imcol
