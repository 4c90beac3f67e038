// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The speed the flow step is scaled by (docs/coupling.md "The flow step"), m/s. Per sphere m:
//   U_m = max(|u_m(0)|, min(U_T,m, U_fall,m))  with gravity (and ρ_m ≠ ρ_f), else |u_m(0)|;
//   U_T,m:    terminal speed on the standard drag curve (Clift, Grace & Weber 1978; the kernel's drag is 2–4 % above it
//             at the default grids, so its terminal speed is below U_T): |ρ_m − ρ_f| g V = ½ ρ_f U² C_D(Re) π a²
//             (C_D held at its Re = 1500 value beyond, where the curve is flat);
//   U_fall,m: a sphere whose weight pulls it toward the wall: √(u(0)² + 2 g' L), g' = |ρ_m − ρ_f| g / (ρ_m + ½ ρ_f)
//             (gravity, buoyancy and the added mass, no drag), L the initial gap (∞ otherwise: a pair can fall together
//             without end, and the frame that follows its midpoint sees its speed as the far stream).
// U_ref = max_m U_m: it bounds the speeds the kernel's grid sees (a wall scene: the sphere's; a pair, in the frame of
// its midpoint: the midpoint's speed and half the relative speed).
#include <span>
#include <string>

#include "core/scene.hpp"

namespace imcol::coupling {

struct ReferenceSpeed {
  double u = 0;        // m/s
  std::string source;  // what gave it, for messages: "the terminal speed of sphere 1"
};

ReferenceSpeed reference_speed(const Scene& sc);
/// The same bound from the spheres' present centres z (m) and velocities u (m/s) instead of the scene's initial ones:
/// what they can still reach (coupling/adaptive_step.hpp).
ReferenceSpeed reference_speed(const Scene& sc, std::span<const double> z, std::span<const double> u);

/// Terminal speed (m/s) of a sphere of diameter D (m), density rho_p in a fluid rho_f, mu (Pa s), |g| (m/s²), on the
/// standard drag curve; 0 when rho_p = rho_f.
double terminal_speed(double D, double rho_p, double rho_f, double mu, double g);

}  // namespace imcol::coupling
