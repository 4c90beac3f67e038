// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The flow kernel's step in a coupled run (docs/coupling.md "The flow step"). The kernel's advection is explicit
// (Adams–Bashforth 2); its viscous term is Crank–Nicolson, which sets no step limit. The fluid near the spheres moves
// faster than they do — (|u_r| + |u_z|) reaches 2 U_ref around a moving sphere and 4 U_ref in the squeezed film
// and in the wake a rebounding sphere runs into (measured, bench/flow_stability.cpp and coupled runs) — and AB2 breaks
// once the fluid's Courant number (|u_r| + |u_z|) Δt/h nears 1, the sooner the less viscosity damps it (larger Re). So
//   Δt = flow.dt if given; else Δt = min(cfl h / U_ref, c τ_p) with
//   U_ref (m/s) the speed the spheres can reach (coupling/reference_speed.hpp: the initial speed, or with gravity the
//   terminal speed or the fall to the wall), h = D / cells, cfl = flow.cfl if given, else
//   cfl(Re, N) = 0.5 min(1, √(P_0 / (Re N))), Re = ρ_f U_ref D / μ, N = cells per D, P_0 = 5600 (0.5 up to
//   Re N = 5600, Re 175 at 32 cells/D; at Re = 1000: 0.30 at 16 cells/D, 0.21 at 32); U_ref = 0: cfl h² / ν.
//   The squeezed film's speed grows like √N (a gap of one cell) and AB2's margin shrinks with the cell Péclet number:
//   measured limits at Re = 966 (gondret_st742): cfl 0.35–0.4 at 16, 0.30–0.35 at 24, 0.25–0.30 at 32 cells/D; the
//   rule keeps 1.2–1.3 below them.
//   τ_p = (m + ½ m_f) / (6π μ a) (s), the smallest over the spheres, c = flow.tau_p_fraction: the kernel's force is
//   explicit in the coupling (f_SIM lags the spheres by a step), so a sphere that the fluid stops within a step
//   (low Re, light spheres) is overshot. Measured at Re 0.15, 3 mm, 1 D from a wall (docs/coupling.md): the speed
//   oscillates from c = 0.35 (nylon, 16 cells/D) and 0.40 (glass, 12) on and grows from 0.5 (nylon) and 0.9–1.0
//   (glass); steel is smooth up to 0.5. Default c = 0.2.
#include <string>

#include "core/scene.hpp"
#include "coupling/reference_speed.hpp"

namespace imcol::coupling {

enum class StepLimit { given, courant, viscous, relaxation };  // flow.dt | cfl h/U_ref | cfl h²/ν (U_ref = 0) | c τ_p

struct FlowStep {
  double dt = 0;       // s
  double cfl = 0;      // the Courant number of U_ref (dt U_ref / h; 0 when flow.dt was given or U_ref = 0)
  double re = 0;       // ρ_f U_ref D / μ
  double u_ref = 0;    // m/s
  double tau_p = 0;    // s, the smallest (m + ½ m_f)/(6π μ a)
  StepLimit limit = StepLimit::given;
  // how dt was chosen, for messages, e.g. "flow.cfl = 0.301 (the default at Re = 966, U_ref = 1.05 m/s: the initial
  // speed of sphere 1), dt = 9.9e-05 s"
  std::string rule;
};

/// The flow step of a coupled scene with finest spacing h (m), U_ref from reference_speed(sc).
FlowStep flow_step(const Scene& sc, double h);
/// The same with a given reference speed u_ref (m/s).
FlowStep flow_step(const Scene& sc, double h, double u_ref);

/// cfl(Re, N) of the rule above.
double default_cfl(double re, int cells_per_diameter);

/// τ_p = (m + ½ m_f) / (6π μ a) of sphere m, s.
double relaxation_time(const Scene& sc, std::size_t m);

/// What to change when a run with this step diverged: "the flow kernel's step is too long for the fluid's speed
/// (RULE): lower flow.cfl or set a smaller flow.dt", or the same for τ_p.
std::string step_advice(const FlowStep& s);

}  // namespace imcol::coupling
