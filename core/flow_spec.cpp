// SPDX-License-Identifier: BSD-3-Clause
#include "core/flow_spec.hpp"

#include "core/toml_reader.hpp"

namespace imcol {

void read_flow_spec(TableReader& r, FlowSpec& f) {
  auto int_in = [&](const char* key, int& field, long lo, long hi) {
    if (auto v = r.integer(key)) {
      if (*v < lo || *v > hi) r.fail(key, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + std::to_string(*v) + ")");
      field = static_cast<int>(*v);
    }
  };
  int_in("cells_per_diameter", f.cells_per_diameter, 4, 512);
  int_in("levels", f.levels, 1, 12);
  r.number_in("r_max", f.r_max, 0.6, 100.0, false, false);
  r.number_in("ahead", f.ahead, 0.1, 100.0, false, false);
  r.number_in("behind", f.behind, 0.1, 100.0, false, false);
  if (r.has("dt") && r.has("cfl")) r.fail("cfl", "give either dt or cfl, not both");
  f.dt = r.number("dt", 0.0);
  if (r.has("dt")) r.positive("dt", f.dt);
  f.cfl = r.number("cfl", f.cfl);
  if (r.has("cfl")) r.in_range("cfl", f.cfl, 0.0, 1.0, true, false);  // absent: 0, the step rule's cfl(Re, N)
  if (r.has("dt") && r.has("tau_p_fraction")) r.fail("tau_p_fraction", "give either dt or tau_p_fraction, not both");
  r.number_in("tau_p_fraction", f.tau_p_fraction, 0.0, 1e6, true, false);
  f.adaptive_step = r.boolean("adaptive_step", f.adaptive_step);
  if (r.has("dt") && r.has("adaptive_step") && f.adaptive_step)
    r.fail("adaptive_step", "applies only without dt (a given dt is kept for the whole run)");
  r.number_in("theta", f.theta, 0.5, 1.0, false, false);
  r.number_in("krylov_tol", f.krylov_tol, 1e-14, 0.1, false, false);
  int_in("krylov_max_iter", f.krylov_max_iter, 1, 100000);
  int_in("krylov_restart", f.krylov_restart, 2, 1000);
  int_in("preconditioner_bins", f.preconditioner_bins, 0, 64);
  int_in("block_probe_stride", f.block_probe_stride, 0, 1000);
  r.number_in("ring_spacing", f.ring_spacing, 0.25, 2.0, false, false);
  r.choice("start", f.start);
  if (r.has("developed_distance") && r.has("developed_time")) r.fail("developed_time", "give either developed_distance or developed_time, not both");
  r.number_in("developed_distance", f.developed_distance, 0.0, 1000.0, true, false);
  f.developed_time = r.number("developed_time", 0.0);
  if (r.has("developed_time")) r.positive("developed_time", f.developed_time);
  if (f.start == FlowStart::impulsive && (r.has("developed_distance") || r.has("developed_time")))
    r.fail(r.has("developed_time") ? "developed_time" : "developed_distance", "applies to start = \"developed\" only");
  r.choice("force_in_step", f.force_in_step);
  f.added_mass_estimate = r.boolean("added_mass_estimate", f.added_mass_estimate);
  r.number_in("min_gap_cells", f.min_gap_cells, 1.0, 10.0, false, false);  // below one cell the rings of the two bodies overlap
  r.number_in("energy_margin", f.energy_margin, 0.0, 1e6, false, false);
  r.number_in("speed_jump", f.speed_jump, 1.0, 1e6, true, false);
  r.number_in("speed_jump_floor", f.speed_jump_floor, 0.0, 1e6, true, false);
  r.number_in("max_wall_hours", f.max_wall_hours, 0.0, 1e4, true, false);
  f.fields = r.boolean("fields", f.fields);
  r.choice("fields_format", f.fields_format);
  r.number_in("fields_every", f.fields_every, 0.0, 1e30, false, false);
  if (!f.fields)
    for (const char* k : {"fields_format", "fields_every"})
      if (r.has(k)) r.fail(k, "applies only with fields = true (fields = false writes no flow fields)");
  r.finish();
}

}  // namespace imcol
