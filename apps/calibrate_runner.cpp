// SPDX-License-Identifier: BSD-3-Clause
#include "apps/calibrate_runner.hpp"

#include <algorithm>
#include <utility>

#include "apps/cluster.hpp"
#include "study/parallel_runs.hpp"

namespace imcol {

calib::Runner cluster_runner(int jobs) {
  calib::Runner r;
  r.run = [jobs](std::size_t n, const std::function<std::string(std::size_t)>& work,
                 const std::function<void(std::size_t, std::string, int)>& done) {
    // At least one thread, also for no items: every rank must ask rank 0 once to learn that there is nothing.
    cluster::run_distributed(n, std::max(1, study::job_count(jobs, n)), work, [&done](std::size_t i, std::string bytes, int rank) {
      done(i, std::move(bytes), rank);
      return true;  // every item runs: a failed evaluation is a result too
    });
  };
  r.share = [](std::string& bytes) { cluster::share(bytes); };
  return r;
}

}  // namespace imcol
