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
  f.r_max = r.number("r_max", f.r_max);
  r.in_range("r_max", f.r_max, 0.6, 100.0, false, false);
  f.ahead = r.number("ahead", f.ahead);
  r.in_range("ahead", f.ahead, 0.1, 100.0, false, false);
  f.behind = r.number("behind", f.behind);
  r.in_range("behind", f.behind, 0.1, 100.0, false, false);
  if (r.has("dt") && r.has("cfl")) r.fail("cfl", "give either dt or cfl, not both");
  f.dt = r.number("dt", 0.0);
  if (r.has("dt")) r.positive("dt", f.dt);
  f.cfl = r.number("cfl", f.cfl);
  if (r.has("cfl")) r.in_range("cfl", f.cfl, 0.0, 1.0, true, false);  // absent: 0, the step rule's cfl(Re, N)
  if (r.has("dt") && r.has("tau_p_fraction")) r.fail("tau_p_fraction", "give either dt or tau_p_fraction, not both");
  f.tau_p_fraction = r.number("tau_p_fraction", f.tau_p_fraction);
  r.in_range("tau_p_fraction", f.tau_p_fraction, 0.0, 1e6, true, false);
  f.theta = r.number("theta", f.theta);
  r.in_range("theta", f.theta, 0.5, 1.0, false, false);
  f.krylov_tol = r.number("krylov_tol", f.krylov_tol);
  r.in_range("krylov_tol", f.krylov_tol, 1e-14, 0.1, false, false);
  int_in("krylov_max_iter", f.krylov_max_iter, 1, 100000);
  int_in("krylov_restart", f.krylov_restart, 2, 1000);
  int_in("preconditioner_bins", f.preconditioner_bins, 1, 64);
  f.ring_spacing = r.number("ring_spacing", f.ring_spacing);
  r.in_range("ring_spacing", f.ring_spacing, 0.25, 2.0, false, false);
  r.choice("start", f.start);
  if (r.has("developed_distance") && r.has("developed_time")) r.fail("developed_time", "give either developed_distance or developed_time, not both");
  f.developed_distance = r.number("developed_distance", f.developed_distance);
  r.in_range("developed_distance", f.developed_distance, 0.0, 1000.0, true, false);
  f.developed_time = r.number("developed_time", 0.0);
  if (r.has("developed_time")) r.positive("developed_time", f.developed_time);
  if (f.start == FlowStart::impulsive && (r.has("developed_distance") || r.has("developed_time")))
    r.fail(r.has("developed_time") ? "developed_time" : "developed_distance", "applies to start = \"developed\" only");
  r.choice("force_in_step", f.force_in_step);
  f.added_mass_estimate = r.boolean("added_mass_estimate", f.added_mass_estimate);
  f.min_gap_cells = r.number("min_gap_cells", f.min_gap_cells);
  r.in_range("min_gap_cells", f.min_gap_cells, 1.0, 10.0, false, false);  // below one cell the rings of the two bodies overlap
  f.energy_margin = r.number("energy_margin", f.energy_margin);
  r.in_range("energy_margin", f.energy_margin, 0.0, 1e6, false, false);
  f.speed_jump = r.number("speed_jump", f.speed_jump);
  r.in_range("speed_jump", f.speed_jump, 1.0, 1e6, true, false);
  f.speed_jump_floor = r.number("speed_jump_floor", f.speed_jump_floor);
  r.in_range("speed_jump_floor", f.speed_jump_floor, 0.0, 1e6, true, false);
  f.max_wall_hours = r.number("max_wall_hours", f.max_wall_hours);
  r.in_range("max_wall_hours", f.max_wall_hours, 0.0, 1e4, true, false);
  f.fields = r.boolean("fields", f.fields);
  r.finish();
}

}  // namespace imcol
