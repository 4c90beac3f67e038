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

/// "key = value" lines.
struct Lines {
  std::string text;
  void put(const std::string& key, const std::string& value) { text += key + " = " + value + "\n"; }
  void solid(const std::string& at, const Solid& s) {
    put(at + ".material", s.material);
    put(at + ".density", num(s.density));
    put(at + ".youngs_modulus", num(s.youngs_modulus));
    put(at + ".poisson_ratio", num(s.poisson_ratio));
    put(at + ".e_dry", num(s.e_dry));
    put(at + ".roughness", num(s.roughness));
  }
};

inline void put_fluid(Lines& o, const Scene& sc) {
  if (sc.fluid) {
    const FluidSpec& f = *sc.fluid;
    o.put("fluid.density", num(f.density));
    o.put("fluid.viscosity", num(f.viscosity));
    o.put("fluid.name", f.name);
    o.put("fluid.mass_fraction", num(f.mass_fraction));
    o.put("fluid.temperature", num(f.temperature));
    o.put("fluid.density_source", f.density_source);
    o.put("fluid.viscosity_source", f.viscosity_source);
  } else {
    o.put("fluid", "none");
  }
}

inline void put_bodies(Lines& o, const Scene& sc) {
  for (std::size_t k = 0; k < sc.spheres.size(); ++k) {
    const SphereSpec& s = sc.spheres[k];
    const std::string at = "sphere." + std::to_string(k);
    o.solid(at, s);
    o.put(at + ".diameter", num(s.diameter));
    o.put(at + ".position", num(s.position));
    o.put(at + ".velocity", num(s.velocity));
  }
  if (sc.wall) {
    o.solid("wall", *sc.wall);
    o.put("wall.position", num(sc.wall->position));
  } else {
    o.put("wall", "none");
  }
}

/// Gravity, the effects and the force models' settings.
inline void put_models(Lines& o, const Scene& sc) {
  o.put("gravity", num(sc.gravity));
  std::string effects;
  for (Effect e : sc.effects) effects += std::string(effects.empty() ? "" : ",") + to_string(e);
  o.put("effects", effects);
  o.put("drag.law", to_string(sc.drag.law));
  o.put("lubrication.model", to_string(sc.lubrication.model));
  o.put("lubrication.cutoff", num(sc.lubrication.cutoff));
  o.put("lubrication.h_c", num(sc.lubrication.h_c));
  o.put("lubrication.limit", to_string(sc.lubrication.limit));
  o.put("lubrication.roughness", num(sc.lubrication.roughness));
  o.put("added_mass.model", to_string(sc.added_mass.model));
  o.put("added_mass.dw_floor", num(sc.added_mass.dw_floor));
  o.put("contact.delta_ss", num(sc.contact.delta_ss));
  o.put("contact.delta_sl", num(sc.contact.delta_sl));
  o.put("contact.e_dry", num(sc.contact.e_dry));
  o.put("contact.beta", num(sc.contact.beta));
  o.put("contact.law", to_string(sc.contact.law));
}

inline void put_history(Lines& o, const Scene& sc) {
  const auto& h = sc.history;
  o.put("history.kernel", to_string(h.kernel));
  o.put("history.evaluator", to_string(h.evaluator));
  o.put("history.tolerance", num(h.tolerance));
  o.put("history.modes", std::to_string(h.modes));
  o.put("history.min_lag", num(h.min_lag));
  o.put("history.horizon", num(h.horizon));
  o.put("history.start", to_string(h.start));
  o.put("history.reynolds", to_string(h.reynolds));
  o.put("history.wall_correction", to_string(h.wall_correction));
  o.put("history.direct_step", num(h.direct_step));
  o.put("history.interpolate_outputs", h.interpolate_outputs ? "true" : "false");
}

inline void put_solver(Lines& o, const Scene& sc) {
  const auto& s = sc.solver;
  o.put("solver.integrator", to_string(s.integrator));
  o.put("solver.linear_solver", to_string(s.linear_solver));
  o.put("solver.krylov_tol", num(s.krylov_tol));
  o.put("solver.rtol", num(s.rtol));
  o.put("solver.atol", num(s.atol));
  o.put("solver.t_end", num(s.t_end));
  o.put("solver.max_step", num(s.max_step));
  o.put("solver.max_steps", std::to_string(s.max_steps));
  o.put("solver.step_budget", num(s.step_budget));
}

inline void put_measure(Lines& o, const Scene& sc) {
  const auto& m = sc.measure;
  o.put("measure.window", num(m.window));
  o.put("measure.instant_gap", num(m.instant_gap));
  o.put("measure.stall_fraction", num(m.stall_fraction));
  o.put("measure.bounces", to_string(m.bounces));
  o.put("measure.fit_distance", num(m.fit_distance));
  o.put("measure.at_gap", num(m.at_gap));
  o.put("measure.e", to_string(m.e));
  o.put("measure.ends_distance", num(m.ends_distance));
  o.put("measure.ends_speed_change", num(m.ends_speed_change));
  o.put("measure.ends_tolerance", num(m.ends_tolerance));
  o.put("measure.samples_per_window", std::to_string(m.samples_per_window));
  o.put("measure.disagreement", num(m.disagreement));
  o.put("measure.energy_budget", m.energy_budget ? "true" : "false");
  o.put("measure.max_samples", num(m.max_samples));
  o.put("output.dt", num(sc.output.dt));
}

inline void put_flow(Lines& o, const Scene& sc) {
  const FlowSpec& f = sc.flow;
  o.put("flow.cells_per_diameter", std::to_string(f.cells_per_diameter));
  o.put("flow.levels", std::to_string(f.levels));
  o.put("flow.r_max", num(f.r_max));
  o.put("flow.ahead", num(f.ahead));
  o.put("flow.behind", num(f.behind));
  o.put("flow.dt", num(f.dt));
  o.put("flow.cfl", num(f.cfl));
  o.put("flow.tau_p_fraction", num(f.tau_p_fraction));
  o.put("flow.adaptive_step", f.adaptive_step ? "true" : "false");
  o.put("flow.theta", num(f.theta));
  o.put("flow.krylov_tol", num(f.krylov_tol));
  o.put("flow.krylov_max_iter", std::to_string(f.krylov_max_iter));
  o.put("flow.krylov_restart", std::to_string(f.krylov_restart));
  o.put("flow.ring_spacing", num(f.ring_spacing));
  o.put("flow.preconditioner_bins", std::to_string(f.preconditioner_bins));
  o.put("flow.block_probe_stride", std::to_string(f.block_probe_stride));
  o.put("flow.start", to_string(f.start));
  o.put("flow.developed_distance", num(f.developed_distance));
  o.put("flow.developed_time", num(f.developed_time));
  o.put("flow.force_in_step", to_string(f.force_in_step));
  o.put("flow.added_mass_estimate", f.added_mass_estimate ? "true" : "false");
  o.put("flow.min_gap_cells", num(f.min_gap_cells));
  o.put("flow.energy_margin", num(f.energy_margin));
  o.put("flow.speed_jump", num(f.speed_jump));
  o.put("flow.speed_jump_floor", num(f.speed_jump_floor));
  o.put("flow.max_wall_hours", num(f.max_wall_hours));
  o.put("flow.fields", f.fields ? "true" : "false");
  o.put("flow.fields_format", to_string(f.fields_format));
  o.put("flow.fields_every", num(f.fields_every));
}

}  // namespace scene_values_detail

/// The scene's values (not its path): equal texts, equal scenes.
inline std::string scene_values(const Scene& sc) {
  scene_values_detail::Lines o;
  o.put("name", sc.name);
  o.put("description", sc.description);
  scene_values_detail::put_fluid(o, sc);
  scene_values_detail::put_bodies(o, sc);
  scene_values_detail::put_models(o, sc);
  scene_values_detail::put_history(o, sc);
  scene_values_detail::put_solver(o, sc);
  scene_values_detail::put_measure(o, sc);
  scene_values_detail::put_flow(o, sc);
  return o.text;
}

}  // namespace imcol
