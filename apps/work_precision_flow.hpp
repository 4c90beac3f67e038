// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol work-precision` on a coupled scene (the `flow` effect): what the flow kernel's accuracy costs. The ladder is
// the grid (cells per diameter) at the scene's flow step rule, then the flow step (cfl) at the scene's grid, each run
// compared with the finest run of its ladder (MODEL.md §5: convergence is in cells per diameter and in Δt).
#include <filesystem>
#include <string>
#include <vector>

#include "apps/output_unit.hpp"
#include "core/scene.hpp"

namespace imcol {

struct FlowLadderOptions {
  std::string out;                                 // default out/<scene>-work_precision
  std::vector<int> cells = {16, 24, 32, 48};       // cells per diameter; the last is the grid ladder's reference
  std::vector<double> cfls = {1.0, 0.5, 0.25};     // flow step dt = cfl h / U; the last is the step ladder's reference
};

/// Prints both ladders (e, |e − e_finest|, e_instant, wall time, flow steps, ms per flow step) and writes
/// DIR/work_precision_flow.csv and .json (DIR: opt.out, or `fallback`). Under mpirun the rungs are spread over the
/// ranks (docs/cluster.md) and rank 0 alone prints and writes.
int work_precision_flow(const Scene& base, const std::vector<Override>& overrides, const FlowLadderOptions& opt,
                        const std::filesystem::path& fallback);

}  // namespace imcol
