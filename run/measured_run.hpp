// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A run for its e (what imcol sweep and imcol calibrate's e tables measure): kinematics only, and rerun with
// solver.t_end doubled, twice at most, while its collision or rebound did not fit in t_end.
#include "core/scene.hpp"
#include "run/simulate.hpp"

namespace imcol {

/// Runs `scene` (Recording::kinematics); while the summary says t_end_too_short, reruns it with solver.t_end doubled
/// (at most twice). The result's scene carries the t_end of the run kept. Throws as simulate does.
RunResult simulate_for_e(const Scene& scene);

}  // namespace imcol
