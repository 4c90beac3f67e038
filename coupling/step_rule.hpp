#pragma once
// The flow kernel's step in a coupled run (docs/coupling.md "The flow step"). The kernel's advection is explicit
// (Adams–Bashforth 2); its viscous term is Crank–Nicolson, which sets no step limit. The fluid near the spheres moves
// faster than they do — (|u_r| + |u_z|) reaches 2 U_ref around a moving sphere and 4 U_ref in the squeezed film
// and in the wake a rebounding sphere runs into (measured, bench/flow_stability.cpp and coupled runs) — and AB2 breaks
// once the fluid's Courant number (|u_r| + |u_z|) Δt/h nears 1, the sooner the less viscosity damps it (larger Re). So
//   Δt = flow.dt if given; else Δt = cfl h / U_ref, U_ref the largest initial sphere speed (m/s), h = D / cells, with
//   cfl = flow.cfl if given, else cfl(Re, N) = 0.5 min(1, √(P_0 / (Re N))), Re = ρ_f U_ref D / μ, N = cells per D,
//   P_0 = 5600 (0.5 up to Re N = 5600; at Re = 1000: 0.30 at 16 cells/D, 0.21 at 32); a scene where nothing moves at
//   t = 0: Δt = cfl h² / ν. The squeezed film's speed grows like √N (a gap of one cell) and AB2's margin shrinks with
//   the cell Péclet number: measured limits at Re = 966 (gondret_st742): cfl 0.35–0.4 at 16, 0.30–0.35 at 24,
//   0.25–0.30 at 32 cells/D; the rule keeps 1.2–1.3 below them.
#include <string>

#include "core/scene.hpp"

namespace imcol::coupling {

struct FlowStep {
  double dt = 0;       // s
  double cfl = 0;      // the Courant number of U_ref that gave dt (0 when flow.dt was given)
  double re = 0;       // ρ_f U_ref D / μ
  std::string rule;    // how dt was chosen, for messages: "flow.cfl = 0.25 (the Re rule, Re = 966), dt = 7.5e-05 s"
};

/// The flow step of a coupled scene with finest spacing h (m) and reference speed u_ref (m/s).
FlowStep flow_step(const Scene& sc, double h, double u_ref);

/// cfl(Re, N) of the rule above.
double default_cfl(double re, int cells_per_diameter);

}  // namespace imcol::coupling
