// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An upper bound of the speed at which the spheres meet (m/s), known before the run:
//   U_imp ≤ |U_rel(0)| + √(2 g' h0),  g' = Σ_m g |1 − ρ_f/ρ_m|  (a fall over the initial gap h0, no drag, no added mass);
// with drag, no sphere is faster than the larger of its initial and its terminal speed (MODEL.md §2.1), so
//   U_imp ≤ max(Σ_m max(|U_m(0)|, U_t,m), |U_rel(0)|).
// It sets the measures' sampling interval and, for a sphere released from rest, the time scales the history force's
// memory must resolve.
#include "core/scene.hpp"
#include "model/pair.hpp"

namespace imcol::model {

double impact_speed_bound(const Scene& sc, const PairGeometry& p);

}  // namespace imcol::model
