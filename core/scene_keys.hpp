// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The keys each table of a collision scene may hold, as its reader (core/scene.cpp, core/flow_spec.cpp) reads them:
// a key outside its table's list is reported as unknown, at its line, with the close keys of the list.
#include <string>
#include <vector>

namespace imcol::scene_keys {

using Keys = std::vector<std::string>;

inline const Keys top = {"name", "description", "fluid", "sphere", "wall", "gravity", "effects", "drag", "lubrication",
                         "added_mass", "contact", "history", "solver", "measure", "flow", "output"};
inline const Keys fluid = {"fluid", "density", "viscosity", "mass_fraction", "temperature"};
inline const Keys sphere = {"material", "density", "youngs_modulus", "poisson_ratio", "e_dry", "diameter", "position", "velocity"};
inline const Keys wall = {"material", "youngs_modulus", "poisson_ratio", "e_dry", "position"};
inline const Keys drag = {"law"};
inline const Keys lubrication = {"model", "cutoff", "h_c", "limit", "roughness"};
inline const Keys added_mass = {"model", "dw_floor"};
inline const Keys contact = {"delta_ss", "delta_sl", "e_dry", "beta", "law"};
inline const Keys history = {"kernel", "evaluator", "tolerance", "modes", "min_lag", "horizon", "start", "reynolds",
                             "wall_correction", "direct_step", "interpolate_outputs"};
inline const Keys solver = {"integrator", "linear_solver", "krylov_tol", "rtol", "atol", "t_end", "max_step", "max_steps",
                            "step_budget"};
inline const Keys measure = {"window", "instant_gap", "stall_fraction", "bounces", "fit_distance", "at_gap", "e",
                             "ends_distance", "ends_speed_change", "ends_tolerance", "samples_per_window", "disagreement",
                             "max_samples", "energy_budget"};
inline const Keys flow = {"cells_per_diameter", "levels", "r_max", "ahead", "behind", "dt", "cfl", "tau_p_fraction", "adaptive_step", "theta",
                          "krylov_tol", "krylov_max_iter", "krylov_restart", "preconditioner_bins", "block_probe_stride",
                          "ring_spacing", "start",
                          "developed_distance", "developed_time", "force_in_step", "added_mass_estimate", "min_gap_cells",
                          "energy_margin", "speed_jump", "speed_jump_floor", "max_wall_hours", "fields", "fields_format",
                          "fields_every"};
inline const Keys output = {"dt"};

}  // namespace imcol::scene_keys
