// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The `[flow]` table of a collision scene: the embedded flow kernel that supplies f_SIM (MODEL.md §2, §2.5, §5).
// Lengths in units of the impact sphere's diameter D, times in s. Read by read_flow_spec(); every key is checked.
#include <string>

#include "core/choices.hpp"

namespace imcol {

class TableReader;

struct FlowSpec {
  int cells_per_diameter = 32;   // finest spacing h = D / cells_per_diameter
  int levels = 4;                // nested levels, each twice the size and spacing of the one inside
  double r_max = 1.0;            // finest level's radius, D (at least r_max × the larger sphere's diameter)
  double ahead = 0.75;           // finest level beyond the leading sphere's surface, D
  double behind = 1.25;          // finest level behind the trailing sphere's surface (its wake), D
  double dt = 0;                 // flow step, s; 0: from cfl
  double cfl = 0;                // dt = cfl h / U_ref (U_ref: coupling/reference_speed.hpp) when dt = 0; 0: cfl(Re, N) of
                                 // coupling/step_rule.hpp (0.5 up to Re N = 5600: Re 175 at 32 cells/D; 0.21 at Re 1000)
  double tau_p_fraction = 0.2;   // and dt ≤ this × τ_p = (m + ½ m_f)/(6π μ a), the smallest over the spheres, when dt = 0
  bool adaptive_step = true;     // re-choose dt as the run goes on, U_ref from the present state (coupling/adaptive_step.hpp);
                                 // only when dt = 0
  double theta = 0.5;            // implicit weight of the viscous term (0.5 Crank–Nicolson)
  double krylov_tol = 1e-4;      // GMRES relative residual of the force system (1e-6 in 0.16.0, 1e-8 before: e within
                                 // 1.0e-6 of 1e-6 on the shipped coupled scenes, docs/coupling.md)
  int krylov_max_iter = 500;
  int krylov_restart = 60;
  double ring_spacing = 1.0;     // arc spacing of the body rings, cells
  int preconditioner_bins = 0;   // GMRES: sub-cell offsets with their own preconditioner block (each probed: 2 ×
                                 // block_probe_stride force solves); 0: chosen from the coupled steps
                                 // (coupling/preconditioner_bins.hpp)
  int block_probe_stride = 12;   // GMRES: a later block is the first one of its sphere radius plus the change of the force
                                 // system probed at every stride-th ring point (2 × stride force solves); 0: each in full
  FlowStart start = FlowStart::developed;
  double developed_distance = 1.0;  // developed: distance the faster sphere travels before t = 0, D
  double developed_time = 0;        // developed: or this time, s (> 0 overrides the distance)
  ForceInStep force_in_step = ForceInStep::linear;
  bool added_mass_estimate = true;  // keep the model's added mass implicit and remove it from f_SIM (false: f_SIM explicit,
                                    // unstable for light spheres; only without the added_mass effect; MODEL.md §5)
  double min_gap_cells = 1.0;    // smallest gap the kernel sees, finest cells, in [1, 10] (closer rings overlap)
  // Divergence checks (coupling/divergence_watch.hpp): the spheres' kinetic energy may exceed what the initial motion
  // and gravity supply by this fraction; a sphere's speed may grow by at most speed_jump times in one flow step (without
  // solid contact), speeds below speed_jump_floor × √(2 E_avail/m) not judged.
  double energy_margin = 0.25;
  double speed_jump = 3.0;
  double speed_jump_floor = 0.5;
  double max_wall_hours = 1.0;   // a run whose estimated wall time (flow/cost.hpp, up to t_end) exceeds this is refused
  bool fields = true;            // write the flow fields and pictures (gap 1 D, contact, one window after separation, end)
  FieldsFormat fields_format = FieldsFormat::both;  // their files: CSV (the pictures read it), VTK XML (ParaView), or both
  double fields_every = 0;       // and every this many seconds from t = 0 (0: only the moments above), s
  int line = 0;                  // line of the [flow] table (0: not given)
};

/// Reads the `[flow]` table (reader positioned on it) into spec; throws InputError naming file:line and key.
void read_flow_spec(TableReader& r, FlowSpec& spec);

}  // namespace imcol
