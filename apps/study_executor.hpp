// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A study's Executor (study/executor.hpp) over the ranks of this MPI job (apps/cluster.hpp): each rank runs its share
// on `jobs` threads; the deciding rank (0) takes every result. One rank alone: this process's threads.
#include "apps/cluster.hpp"
#include "study/executor.hpp"

namespace imcol {

inline study::Executor cluster_executor(int jobs) {
  const cluster::World w = cluster::world();
  study::Executor ex = study::threads(jobs);
  ex.rank = w.rank, ex.ranks = w.size;
  if (w.size == 1) return ex;
  ex.distribute = [rank = w.rank](std::size_t n, int threads, const std::function<std::string(std::size_t)>& work,
                                  const std::function<bool(std::size_t, std::string, int)>& done) {
    cluster::run_distributed(n, threads, work, rank == 0 ? done : std::function<bool(std::size_t, std::string, int)>());
  };
  return ex;
}

}  // namespace imcol
