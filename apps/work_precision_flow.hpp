// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol work-precision` on a coupled scene (the `flow` effect): the grid and flow-step ladders of
// study/work_precision_flow.hpp, printed and written.
#include <filesystem>
#include <string>
#include <vector>

#include "apps/output_unit.hpp"
#include "core/scene.hpp"
#include "study/work_precision_flow.hpp"

namespace imcol {

struct FlowLadderOptions : study::FlowLadderOptions {
  std::string out;  // default out/<scene>-work_precision
};

/// Prints both ladders (e, |e − e_finest|, e_instant, wall time, flow steps, ms per flow step) and writes
/// DIR/work_precision_flow.csv and .json (DIR: opt.out, or `fallback`). Under mpirun the rungs are spread over the
/// ranks (docs/cluster.md) and rank 0 alone prints and writes.
int work_precision_flow(const Scene& base, const std::vector<Override>& overrides, const FlowLadderOptions& opt,
                        const std::filesystem::path& fallback);

}  // namespace imcol
