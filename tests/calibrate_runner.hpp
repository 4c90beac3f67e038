// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// For the calibration engine's tests: the shipped scene they calibrate, and a Runner that does work items on a few
// threads of this process, one at a time.
#include <atomic>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "calibrate/search.hpp"
#include "core/materials.hpp"

namespace imcol::test {

/// The shipped scene of the seed's case gg3462.
inline std::string gg3462() { return data_dir() + "/scenes/gg3462.toml"; }

inline calib::Runner thread_runner(int threads) {
  calib::Runner r;
  r.run = [threads](std::size_t n, const std::function<std::string(std::size_t)>& work,
                    const std::function<void(std::size_t, std::string, int)>& done) {
    std::atomic<std::size_t> next{0};
    std::mutex mu;
    auto worker = [&] {
      for (std::size_t i = next++; i < n; i = next++) {
        std::string bytes = work(i);
        std::lock_guard lock(mu);
        done(i, std::move(bytes), 0);
      }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  };
  r.share = [](std::string&) {};  // one process: rank 0's bytes are everyone's
  return r;
}

}  // namespace imcol::test
