// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Every value of a resolved Scene as text, one "key = value" line each (doubles to 17 digits, so that two scenes have
// the same text exactly when they hold the same values): what the ranks of an MPI job compare (apps/cluster.hpp
// agree). The materials and liquids the scene named are there as the values they resolved to, so the text also differs
// when two ranks read different data files. A field added to Scene or FlowSpec must be added here
// (tests/test_scene_values.cpp sets every scene key and checks that the text changes).
#include <cstdio>
#include <optional>
#include <string>

#include "core/scene.hpp"

namespace imcol {

namespace scene_values_detail {

inline std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
inline std::string num(const std::optional<double>& v) { return v ? num(*v) : std::string("none"); }

inline void solid(std::string& out, const std::string& at, const Solid& s) {
  out += at + ".material = " + s.material + "\n";
  out += at + ".density = " + num(s.density) + "\n";
  out += at + ".youngs_modulus = " + num(s.youngs_modulus) + "\n";
  out += at + ".poisson_ratio = " + num(s.poisson_ratio) + "\n";
  out += at + ".e_dry = " + num(s.e_dry) + "\n";
  out += at + ".roughness = " + num(s.roughness) + "\n";
}

}  // namespace scene_values_detail

/// The scene's values (not its path): equal texts, equal scenes.
inline std::string scene_values(const Scene& sc) {
  using scene_values_detail::num;
  std::string o;
  auto put = [&o](const std::string& key, const std::string& value) { o += key + " = " + value + "\n"; };
  put("name", sc.name);
  put("description", sc.description);
  if (sc.fluid) {
    const FluidSpec& f = *sc.fluid;
    put("fluid.density", num(f.density));
    put("fluid.viscosity", num(f.viscosity));
    put("fluid.name", f.name);
    put("fluid.mass_fraction", num(f.mass_fraction));
    put("fluid.temperature", num(f.temperature));
    put("fluid.density_source", f.density_source);
    put("fluid.viscosity_source", f.viscosity_source);
  } else {
    put("fluid", "none");
  }
  for (std::size_t k = 0; k < sc.spheres.size(); ++k) {
    const SphereSpec& s = sc.spheres[k];
    const std::string at = "sphere." + std::to_string(k);
    scene_values_detail::solid(o, at, s);
    put(at + ".diameter", num(s.diameter));
    put(at + ".position", num(s.position));
    put(at + ".velocity", num(s.velocity));
  }
  if (sc.wall) {
    scene_values_detail::solid(o, "wall", *sc.wall);
    put("wall.position", num(sc.wall->position));
  } else {
    put("wall", "none");
  }
  put("gravity", num(sc.gravity));
  std::string effects;
  for (Effect e : sc.effects) effects += std::string(effects.empty() ? "" : ",") + to_string(e);
  put("effects", effects);
  put("drag.law", to_string(sc.drag.law));
  put("lubrication.model", to_string(sc.lubrication.model));
  put("lubrication.cutoff", num(sc.lubrication.cutoff));
  put("lubrication.h_c", num(sc.lubrication.h_c));
  put("lubrication.limit", to_string(sc.lubrication.limit));
  put("lubrication.roughness", num(sc.lubrication.roughness));
  put("added_mass.model", to_string(sc.added_mass.model));
  put("added_mass.dw_floor", num(sc.added_mass.dw_floor));
  put("contact.delta_ss", num(sc.contact.delta_ss));
  put("contact.delta_sl", num(sc.contact.delta_sl));
  put("contact.e_dry", num(sc.contact.e_dry));
  put("contact.beta", num(sc.contact.beta));
  put("contact.law", to_string(sc.contact.law));
  const auto& h = sc.history;
  put("history.kernel", to_string(h.kernel));
  put("history.evaluator", to_string(h.evaluator));
  put("history.tolerance", num(h.tolerance));
  put("history.modes", std::to_string(h.modes));
  put("history.min_lag", num(h.min_lag));
  put("history.horizon", num(h.horizon));
  put("history.start", to_string(h.start));
  put("history.reynolds", to_string(h.reynolds));
  put("history.wall_correction", to_string(h.wall_correction));
  put("history.direct_step", num(h.direct_step));
  const auto& s = sc.solver;
  put("solver.integrator", to_string(s.integrator));
  put("solver.linear_solver", to_string(s.linear_solver));
  put("solver.krylov_tol", num(s.krylov_tol));
  put("solver.rtol", num(s.rtol));
  put("solver.atol", num(s.atol));
  put("solver.t_end", num(s.t_end));
  put("solver.max_step", num(s.max_step));
  put("solver.max_steps", std::to_string(s.max_steps));
  put("solver.step_budget", num(s.step_budget));
  const auto& m = sc.measure;
  put("measure.window", num(m.window));
  put("measure.instant_gap", num(m.instant_gap));
  put("measure.stall_fraction", num(m.stall_fraction));
  put("measure.bounces", to_string(m.bounces));
  put("measure.fit_distance", num(m.fit_distance));
  put("measure.at_gap", num(m.at_gap));
  put("measure.e", to_string(m.e));
  put("measure.ends_distance", num(m.ends_distance));
  put("measure.ends_speed_change", num(m.ends_speed_change));
  put("measure.ends_tolerance", num(m.ends_tolerance));
  put("measure.samples_per_window", std::to_string(m.samples_per_window));
  put("measure.disagreement", num(m.disagreement));
  put("measure.energy_budget", m.energy_budget ? "true" : "false");
  put("measure.max_samples", num(m.max_samples));
  put("output.dt", num(sc.output.dt));
  const FlowSpec& f = sc.flow;
  put("flow.cells_per_diameter", std::to_string(f.cells_per_diameter));
  put("flow.levels", std::to_string(f.levels));
  put("flow.r_max", num(f.r_max));
  put("flow.ahead", num(f.ahead));
  put("flow.behind", num(f.behind));
  put("flow.dt", num(f.dt));
  put("flow.cfl", num(f.cfl));
  put("flow.tau_p_fraction", num(f.tau_p_fraction));
  put("flow.theta", num(f.theta));
  put("flow.krylov_tol", num(f.krylov_tol));
  put("flow.krylov_max_iter", std::to_string(f.krylov_max_iter));
  put("flow.krylov_restart", std::to_string(f.krylov_restart));
  put("flow.ring_spacing", num(f.ring_spacing));
  put("flow.preconditioner_bins", std::to_string(f.preconditioner_bins));
  put("flow.start", to_string(f.start));
  put("flow.developed_distance", num(f.developed_distance));
  put("flow.developed_time", num(f.developed_time));
  put("flow.force_in_step", to_string(f.force_in_step));
  put("flow.added_mass_estimate", f.added_mass_estimate ? "true" : "false");
  put("flow.min_gap_cells", num(f.min_gap_cells));
  put("flow.energy_margin", num(f.energy_margin));
  put("flow.speed_jump", num(f.speed_jump));
  put("flow.speed_jump_floor", num(f.speed_jump_floor));
  put("flow.max_wall_hours", num(f.max_wall_hours));
  put("flow.fields", f.fields ? "true" : "false");
  put("flow.fields_format", to_string(f.fields_format));
  put("flow.fields_every", num(f.fields_every));
  return o;
}

}  // namespace imcol
