// SPDX-License-Identifier: BSD-3-Clause
#include "run/flow_run_json.hpp"

namespace imcol {

namespace {

using json = nlohmann::ordered_json;

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(); }

void add_drag(json& j, const FlowDragComparison& d) {
  j["drag_coefficient"] = d.coefficient;
  j["drag_change_last_tenth_percent"] = d.change_last_tenth_percent;
  j["drag_settled"] = d.settled;
  j["drag_left_to_settle_percent"] = d.left_to_settle_percent;  // extrapolated, t^(-1/2) tail
  j["distance_passed_D"] = d.distance_passed_D;
  j["drag_coefficient_standard"] = optional_number(d.standard);
  j["drag_error_percent"] = optional_number(d.error_percent);
  j["stokes_drag_ratio"] = d.stokes_drag_ratio;  // F / 6πμaU
}

void add_one_sphere(json& j, const FlowOneSphere& s) {
  j["wake_length_D"] = optional_number(s.wake_length_D);  // steady runs in a stream only
  j["time_to_3pct_s"] = optional_number(s.time_to_3pct_s);
  j["wall_time_to_3pct_s"] = optional_number(s.wall_time_to_3pct_s);
  if (const auto& b = s.impulsive_start)
    j["impulsive_start"] = {{"reference", "F = 6 pi mu a U (1 + a / sqrt(pi nu t)), t > 0"},
                            {"window", "0.8 <= nu t / a^2 <= 4"},
                            {"window_t", {b->window_t0, b->window_t1}},
                            {"max_rel_error", b->max_rel_error}};
}

json gap_forces_json(const std::vector<FlowGapForces>& rows) {
  json out = json::array();
  for (const auto& r : rows) {
    json row = {{"gap_D", r.gap_D}, {"gap_cells", r.gap_cells}, {"resolved", r.resolved}, {"F1", r.F1}, {"F_THR1", r.F_THR1}};
    if (r.F2) row["F2"] = *r.F2;
    if (r.F_THR2) row["F_THR2"] = *r.F_THR2;
    if (r.F_wall) row["F_wall"] = *r.F_wall;
    out.push_back(row);
  }
  return out;
}

json grid_json(const FlowGrid& g) {
  auto box = [](const FlowGridBox& b) { return json{{"r_max", b.r_max}, {"z_min", b.z_min}, {"z_max", b.z_max}}; };
  return {{"cells_per_diameter", g.cells_per_diameter},
          {"h", g.h},
          {"levels", g.levels},
          {"nr", g.nr},
          {"nz", g.nz},
          {"finest", box(g.finest)},
          {"coarsest", box(g.coarsest)},
          {"body_points", g.body_points}};
}

void add_grid_and_solver(json& j, const FlowRunResult& r) {
  j["grid"] = grid_json(r.grid);
  j["dt"] = r.dt;
  j["theta"] = r.theta;
  j["steps"] = r.steps;
  j["t_end"] = r.t_end;
  j["wall_time_s"] = r.wall_time_s;
  j["ms_per_step"] = r.ms_per_step;
  j["memory_bytes"] = r.memory_bytes;
  const FlowForceSolver& f = r.force_solver;
  j["force_solver"] = {{"krylov_tol", f.krylov_tol}, {"krylov_iterations_mean", f.krylov_iterations_mean},
                       {"krylov_iterations_max", f.krylov_iterations_max}, {"max_slip", f.max_slip}};
}

/// The wall and the oscillating sphere's comparison, when the scene has them.
void add_wall_and_oscillating(json& j, const FlowRunResult& r) {
  if (r.wall)
    j["wall"] = {{"position", r.wall->position}, {"force_N", r.wall->force_N},
                 {"f_thr", r.wall->brenner ? "Brenner (1961): -lambda(h/a) 6 pi mu a U, quasi-steady Stokes" : ""}};
  if (r.oscillating)
    j["oscillating"] = {{"reference", "F = -6 pi mu a (1 + a/delta) U - 3 pi a^2 sqrt(2 mu rho/omega) (1 + 2a/(9 delta)) dU/dt, at mid-step"},
                        {"delta_over_a", r.oscillating->delta_over_a},
                        {"max_error_last_period_rel_amplitude", r.oscillating->max_error_rel_amplitude}};
}

}  // namespace

json flow_summary_json(const FlowRunResult& r) {
  json j;
  j["scene"] = r.scene;
  j["name"] = r.name;
  j["Re"] = r.Re;
  add_drag(j, r.drag);
  if (r.one_sphere) add_one_sphere(j, *r.one_sphere);
  j["forces_N"] = r.forces_N;
  if (r.gap) {
    j["min_gap_D"] = r.gap->min_gap_D;
    j["gap_resolved"] = r.gap->resolved;  // false: the forces below a 3-cell gap are not resolved
  }
  if (r.gap_forces) j["f_sim_vs_f_thr"] = gap_forces_json(*r.gap_forces);
  add_wall_and_oscillating(j, r);
  add_grid_and_solver(j, r);
  return j;
}

}  // namespace imcol
