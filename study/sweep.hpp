// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A sweep: e against St over values of one scene quantity, every point's scene run on an Executor.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "study/executor.hpp"
#include "study/sweep_points.hpp"

namespace imcol::study {

struct SweepResult {
  std::string vary, column;    // the varied quantity and its CSV column ("velocity_m_s")
  std::vector<double> values;  // of the varied quantity, one per point
  std::vector<SweepPoint> points;
  std::vector<bool> done;      // the point ran (ok or failed); false: not run (cancelled or stopped)
  bool cancelled = false;      // some points were not handed out
  std::size_t finished() const;
  std::size_t failed() const;  // points that ran and failed
};

/// After each point is taken in, on the deciding process, one call at a time: the point's index and the result so
/// far. Returns false to hand out no further points.
using PointTaken = std::function<bool(std::size_t i, const SweepResult& so_far)>;

/// Runs every point (scenes[i] at values[i], run_sweep_point) on `ex`. On a process that is not the deciding one the
/// result holds the values only.
SweepResult run_sweep(const std::vector<Scene>& scenes, const std::string& vary, const std::vector<double>& values, const Executor& ex,
                      const Hooks& hooks = {}, const PointTaken& taken = {});

}  // namespace imcol::study
