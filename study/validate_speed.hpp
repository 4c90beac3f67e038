// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The seed validation's St_B set (study/validate.hpp): a Table 6.1 run's approach speed scaled until the run's St_B(Table 6.1)
// is the printed St_B.
#include <functional>
#include <optional>
#include <vector>

#include "core/scene.hpp"

namespace imcol::study {

/// The overrides that run a pair scene at `scale` times its approach speed: every sphere's velocity times scale and
/// the starting gap times scale (the same time before contact, about 30 ms in the seed_run scenes).
std::vector<Override> speed_overrides(const Scene& sc, double scale);

/// The scene's approach speed, U_rel at the start (m/s).
double approach_speed(const Scene& sc);

/// The scale that makes St(scale) = St_target, given St(1) = St_1: St_target / St_1 first (St is about linear in the
/// approach speed), then one secant step if St is still more than `tol` (relative) off. `St_at(scale)` runs the scene
/// at that scale and returns its St; the returned scale is the last one run.
double scale_to_St(double St_1, double St_target, const std::function<std::optional<double>(double)>& St_at, double tol = 0.01);

}  // namespace imcol::study
