// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A run for its e (what imcol sweep and imcol calibrate's e tables measure): kinematics only, and rerun with
// solver.t_end doubled, twice at most, while its collision or rebound did not fit in t_end.
#include <string>

#include "core/scene.hpp"
#include "run/simulate.hpp"

namespace imcol {

/// Runs `scene` (Recording::kinematics); while the summary says t_end_too_short, reruns it with solver.t_end doubled
/// (at most twice). The result's scene carries the t_end of the run kept. Throws as simulate does.
RunResult simulate_for_e(const Scene& scene);

/// Why such a run has no e, as sweep and calibrate say it: "e not measured: REASON", without the summary's hint to
/// raise solver.t_end, and "; still so with solver.t_end raised to T s" when t_end_run (the run kept) exceeds the
/// scene's and the collision still did not fit.
std::string e_missing_message(const RunSummary& s, double t_end_scene, double t_end_run);

}  // namespace imcol
