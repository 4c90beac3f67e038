// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where `imcol calibrate` runs its work items: over the ranks of an MPI job (apps/cluster.hpp), each rank on `jobs`
// threads; on one process's threads without mpirun.
#include "calibrate/search.hpp"

namespace imcol {

/// A calib::Runner over cluster::run_distributed and cluster::share; `jobs` threads a rank (0 = all cores), at most
/// one per work item.
calib::Runner cluster_runner(int jobs);

}  // namespace imcol
