// SPDX-License-Identifier: BSD-3-Clause
#include "run/summary.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "run/json_util.hpp"

namespace imcol::run {

using model::CollisionModel;

namespace {

std::optional<double> number_or_none(const nlohmann::ordered_json& j) {
  return j.is_number() ? std::optional<double>(j.get<double>()) : std::nullopt;
}

/// One contact of measure_bounces as a BounceSummary.
BounceSummary typed_bounce(const nlohmann::ordered_json& b) {
  BounceSummary x;
  x.contact = b["contact"].get<int>();
  x.t_contact_s = b["t_contact_s"].get<double>();
  x.t_separation_s = number_or_none(b["t_separation_s"]);
  x.e = number_or_none(b["e"]);
  x.impact_velocity_m_s = number_or_none(b["impact_velocity_m_s"]);
  x.rebound_velocity_m_s = number_or_none(b["rebound_velocity_m_s"]);
  x.e_instant = number_or_none(b["e_instant"]);
  x.apex_gap_m = number_or_none(b.value("apex_gap_m", nlohmann::ordered_json(nullptr)));
  x.t_apex_s = number_or_none(b.value("t_apex_s", nlohmann::ordered_json(nullptr)));
  return x;
}

nlohmann::ordered_json or_null(const std::optional<std::string>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

/// The collision phase's dissipation by force (above 5e-4 of the impact energy) and the largest |closure| of a phase.
void put_energy(RunSummary& s, const nlohmann::ordered_json& budget) {
  if (!budget.is_object()) return;
  double closure = 0;
  for (const auto& p : budget["phases"]) {
    closure = std::max(closure, std::abs(p["closure_per_impact_energy"].get<double>()));
    if (p["phase"] != "collision") continue;
    for (const auto& [force, d] : p["dissipated_per_impact_energy"].items())
      if (std::abs(d.get<double>()) > 5e-4) s.dissipated_share.push_back({force, d.get<double>()});
  }
  s.energy_closure = closure;
}

}  // namespace

void measure_summary(RunSummary& s, const CollisionModel& model, const Watch& watch, const Scene& sc, const FirstContact& m,
                     const nlohmann::ordered_json& bounces, const Recorder& rec, const std::vector<std::vector<double>>& rows) {
  const bool pair = model.n_spheres() == 2;
  s.e = m.e;
  s.e_is = to_string(sc.measure.e);  // the named measure in e_measures (measure.e; docs/bounces.md)
  s.e_fit_raw = m.e_fit_raw;
  if (!m.e) s.e_missing = m.e_missing;
  s.e_by_measure = m.e_by_measure;
  s.e_instant = m.e_instant;
  s.e_instant_gap_m = sc.measure.instant_gap * 2 * model.radius(0);
  // The named measures of the first contact (each contact's are in `bounces`).
  if (!bounces.empty()) {
    for (const auto& [name, x] : bounces[0]["e_measures"].items())
      s.e_measures.push_back({*choice_from_string<EMeasure>(name), number_or_none(x.value("e", nlohmann::ordered_json(nullptr)))});
    for (const auto& [name, x] : bounces[0]["measures_disagree"].items()) s.measures_disagree.push_back({name, x.get<double>()});
    put_energy(s, bounces[0]["energy_budget"]);
  }
  s.bounces_mode = to_string(sc.measure.bounces);
  for (const auto& b : bounces) s.bounces.push_back(typed_bounce(b));
  s.St = m.St;
  if (pair) {
    // Both conventions, named (docs/model-notes.md): `St` is St_B_table_6_1.
    s.St_convention = "St_B_table_6_1: seed Table 6.1, half of eq. (6.2); (1/9)(rho_harm/rho_f) Re_rel for equal spheres";
    s.St_B_table_6_1 = m.St;
    s.St_B_eq_6_2 = m.St_62;
  } else {
    s.St_convention = "m U / (6 pi mu a^2)";
    // Legendre, Zenit, Daniel & Guiraud (2006): the particle's inertia with half the displaced fluid's,
    // St_L = (rho_p + rho_f/2) U d / (9 mu), the variable of their correlation e/e_dry = exp(-35/St_L).
    if (m.St && sc.fluid && model.has_target()) s.St_L = *m.St * (1 + 0.5 * model.fluid_mass(0) / model.mass(0));
  }
  s.Re = m.Re;
  if (sc.fluid && model.has_target()) s.St_initial = stokes_numbers(model, sc, model.initial_u_rel()).first;  // nominal, same convention
  s.separated = m.separated;
  // The run ended because the pair came to rest (MODEL.md §3 has no event for it; see run/watch_rest.hpp).
  s.at_rest_since_s = watch.rest.since();
  s.t_end_too_short = m.t_end_too_short;
  if (model.has_target()) s.final_phase = model::to_string(model.phase());
  s.contacts = model.contacts();
  s.U_i1 = m.u_i1;
  s.U_i2 = m.u_i2;
  s.U_r1 = m.u_r1;
  s.U_r2 = m.u_r2;
  s.fit_window_s = m.fit_window;
  if (model.has_target()) s.min_gap_m = rec.min_gap();
  if (rec.forces()) s.max_contact_force_N = rec.max_contact_force();
  s.group_velocity_m_s = m.group_velocity;
  if (m.group_velocity) s.group_velocity_at_s = m.t_group;
  if (sc.has(Effect::history) && rec.forces()) s.max_history_force_N = rec.max_history_force();  // at the output samples, events and the steps near contact
  if (!rows.empty()) {
    s.u1_final_m_s = rows.back()[2];
    if (pair) s.u2_final_m_s = rows.back()[5];
  }
}

void put_measurements(nlohmann::ordered_json& j, const RunSummary& s, const Scene& sc, const nlohmann::ordered_json& bounces) {
  const bool pair = s.configuration == Configuration::sphere_sphere;
  j["e"] = or_null(s.e);
  j["e_is"] = s.e_is;
  if (s.e_fit_raw) j["e_fit_raw"] = *s.e_fit_raw;
  if (!s.e) j["e_missing"] = or_null(s.e_missing);
  j["e_instant"] = or_null(s.e_instant);
  j["e_instant_gap_m"] = s.e_instant_gap_m;
  if (!bounces.empty()) {
    j["e_measures"] = bounces[0]["e_measures"];
    j["measures_disagree"] = bounces[0]["measures_disagree"];
    j["energy_budget"] = bounces[0]["energy_budget"];
  } else {
    j["e_measures"] = nullptr;
  }
  j["bounces_mode"] = s.bounces_mode;
  j["bounces"] = bounces;
  j["St"] = or_null(s.St);
  j["St_convention"] = s.St_convention;
  if (pair) {
    j["St_B_table_6_1"] = or_null(s.St_B_table_6_1);
    j["St_B_eq_6_2"] = or_null(s.St_B_eq_6_2);
  } else {
    j["St_L"] = or_null(s.St_L);
  }
  j["Re"] = or_null(s.Re);
  if (s.St_initial) j["St_initial"] = *s.St_initial;
  j["separated"] = s.separated;
  j["at_rest_since_s"] = or_null(s.at_rest_since_s);
  j["t_end_too_short"] = s.t_end_too_short;
  if (s.final_phase) j["final_phase"] = *s.final_phase;
  j["contacts"] = s.contacts;
  j["velocities_m_s"] = {{"U_i1", or_null(s.U_i1)}, {"U_i2", or_null(s.U_i2)}, {"U_r1", or_null(s.U_r1)}, {"U_r2", or_null(s.U_r2)}};
  j["fit_window_s"] = s.fit_window_s;
  j["min_gap_m"] = or_null(s.min_gap_m);
  j["max_contact_force_N"] = or_null(s.max_contact_force_N);
  j["group_velocity_m_s"] = or_null(s.group_velocity_m_s);
  if (s.group_velocity_at_s) j["group_velocity_at_s"] = *s.group_velocity_at_s;
  if (sc.has(Effect::history)) j["max_history_force_N"] = or_null(s.max_history_force_N);
  if (s.u1_final_m_s) j["u1_final_m_s"] = *s.u1_final_m_s;
  if (s.u2_final_m_s) j["u2_final_m_s"] = *s.u2_final_m_s;
}

ContactSummary contact_summary(const CollisionModel& model) {
  const contact::ContactLaw& law = *model.contact_law();
  ContactSummary c;
  c.law = to_string(law.kind());
  c.t_contact_s = model.t_contact();
  c.t_separation_s = model.t_separation();
  if (model.t_contact()) c.impact_speed_m_s = model.impact_speed();
  for (const auto& v : law.summary()) c.law_numbers.push_back({v.name, v.value});  // the law's own numbers
  c.e_dry = model.e_dry();
  c.delta_ss_m = model.delta_ss_m();
  return c;
}

nlohmann::ordered_json contact_block(const ContactSummary& c) {
  nlohmann::ordered_json j = {{"law", c.law},
                              {"t_contact_s", or_null(c.t_contact_s)},
                              {"t_separation_s", or_null(c.t_separation_s)},
                              {"impact_speed_m_s", or_null(c.impact_speed_m_s)}};
  for (const auto& [name, v] : c.law_numbers) j[name] = or_null(v);
  j["e_dry"] = c.e_dry;
  j["delta_ss_m"] = c.delta_ss_m;
  return j;
}

nlohmann::ordered_json solver_block(const CollisionModel& model, const IntegratorSettings& st, const SolverStats& stats, double t_final) {
  nlohmann::ordered_json sol = {{"integrator", to_string(st.method)}, {"linear_solver", stats.linear_solver},
                                {"rtol", st.rtol}, {"atol", st.atol},
                                {"absolute_tolerances", model.absolute_tolerances(st.atol)},
                                {"state", model.component_names()}, {"max_step_s", model.max_step_outside_contact()},
                                {"t_final_s", t_final}};
  for (const auto& [k, v] : stats.as_map()) sol[k] = v;
  return sol;
}

FlowSummary flow_summary(const coupling::FlowRunStats& fs, const Scene& sc, double wall) {
  FlowSummary f;
  f.stats = fs;
  f.start = to_string(sc.flow.start);
  f.force_in_step = to_string(sc.flow.force_in_step);
  f.ms_per_step = fs.steps ? 1e3 * fs.flow_seconds / fs.steps : 0.0;
  f.krylov_iterations_per_step = fs.steps ? double(fs.krylov_iterations) / fs.steps : 0.0;
  f.flow_share = wall > 0 ? fs.flow_seconds / wall : 0.0;
  f.ode_share = wall > 0 ? fs.ode_seconds / wall : 0.0;
  return f;
}

nlohmann::ordered_json flow_block(const FlowSummary& f) {
  const coupling::FlowRunStats& fs = f.stats;
  return {{"grid", {{"cells_per_diameter", fs.cells_per_diameter}, {"h_m", fs.h}, {"nr", fs.nr}, {"nz", fs.nz},
                    {"levels", fs.levels}, {"memory_MB", fs.bytes / 1e6}}},
          {"dt_s", fs.dt}, {"cfl", fs.cfl}, {"max_courant", fs.max_courant}, {"max_energy_ratio", fs.max_energy_ratio}, {"start", f.start}, {"start_up_steps", fs.pre_steps},
          {"force_in_step", f.force_in_step}, {"steps", fs.steps}, {"ms_per_step", f.ms_per_step},
          {"krylov_iterations", fs.krylov_iterations},
          {"krylov_iterations_per_step", f.krylov_iterations_per_step},
          {"max_krylov_iterations", fs.max_krylov_iterations}, {"max_krylov_residual", fs.max_krylov_residual},
          {"max_slip_m_s", fs.max_slip}, {"min_gap_clamped_steps", fs.min_gap_clamped_steps},
          {"frame_travel_m", fs.frame_travel}, {"start_up_time_s", fs.pre_seconds},
          {"flow_time_s", fs.flow_seconds}, {"ode_time_s", fs.ode_seconds},
          {"flow_share", f.flow_share}, {"ode_share", f.ode_share},
          {"field_snapshots", fs.field_snapshots}, {"fields_time_s", fs.fields_seconds},
          {"estimate", {{"start_up_s", fs.est_start_up_s}, {"force_system_blocks_s", fs.est_blocks_s}, {"steps_to_t_end_s", fs.est_steps_s},
                        {"total_s", fs.est_total_s()}, {"memory_MB", fs.est_bytes / 1e6}}}};
}

nlohmann::ordered_json fluid_block(const FluidSpec& f) {
  nlohmann::ordered_json j;
  j["name"] = f.name.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(f.name);
  j["mass_fraction"] = or_null(f.mass_fraction);
  j["temperature_C"] = or_null(f.temperature);
  j["density_kg_m3"] = f.density;
  j["viscosity_Pa_s"] = f.viscosity;
  j["density_source"] = f.density_source;
  j["viscosity_source"] = f.viscosity_source;
  return j;
}

std::string fluid_line(const FluidSpec& f) {
  std::ostringstream os;
  os << "fluid: ";
  if (f.name.empty()) {
    os << "rho = " << std::setprecision(5) << f.density << " kg/m3, mu = " << std::setprecision(4) << f.viscosity << " Pa s (given in the scene)";
    return os.str();
  }
  os << f.name;
  if (f.mass_fraction) os << ", w = " << std::setprecision(4) << *f.mass_fraction;
  if (f.temperature) os << ", " << std::setprecision(4) << *f.temperature << " °C";
  // The source up to its year: "Cheng (2008)" (a source without one, whole); an inline value is "inline".
  auto src = [](const std::string& s) {
    const auto year_end = s.find(')');
    return s == "scene" ? std::string("inline") : year_end == std::string::npos ? s : s.substr(0, year_end + 1);
  };
  os << ": rho = " << std::setprecision(5) << f.density << " kg/m3 (" << src(f.density_source) << "), mu = " << std::setprecision(4)
     << f.viscosity << " Pa s (" << src(f.viscosity_source) << ")";
  return os.str();
}

std::string human_summary(const RunSummary& s) {
  std::ostringstream os;
  auto num = [](const std::optional<double>& v, int prec = 4) {
    if (!v) return std::string("n/a");
    std::ostringstream o;
    o << std::setprecision(prec) << *v;
    return o.str();
  };
  os << "scene " << s.scene << " (" << to_string(s.configuration) << ")\n";
  if (s.fluid) os << "  " << fluid_line(*s.fluid) << "\n";
  os << "  e = " << num(s.e) << " (" << s.e_is << ")   e_instant = " << num(s.e_instant) << "   St = " << num(s.St);
  if (s.configuration == Configuration::sphere_sphere) os << " (St_B, Table 6.1; eq. 6.2: " << num(s.St_B_eq_6_2) << ")";
  if (s.St_L) os << "   St_L = " << num(s.St_L);
  os << "   Re = " << num(s.Re) << "\n";
  if (s.e_by_measure) os << "  e by measure: " << *s.e_by_measure << "\n";
  if (!s.dissipated_share.empty()) {
    os << "  of the impact kinetic energy, dissipated over the collision by:" << std::fixed << std::setprecision(3);
    for (const auto& [force, d] : s.dissipated_share) os << " " << force << " " << d;
    os << std::defaultfloat << std::setprecision(2) << " (budget closes to " << *s.energy_closure << ")\n";
  }
  if (s.group_velocity_m_s)
    os << "  group velocity = " << num(s.group_velocity_m_s) << " m/s (no separation; centre-of-mass velocity at t = "
       << num(s.group_velocity_at_s) << " s, when the relative velocity vanished)\n";
  if (s.at_rest_since_s)
    os << "  at rest from t = " << num(s.at_rest_since_s) << " s (|U_rel| and |dU_rel/dt| x measure.window below stall_fraction x the"
       << " impact speed for one window): the run ended there\n";
  if (s.min_gap_m) os << "  min gap = " << num(s.min_gap_m) << " m, max contact force = " << num(s.max_contact_force_N) << " N\n";
  std::string eff;
  for (const auto& x : s.effects) eff += (eff.empty() ? "" : ", ") + x;
  os << "  effects: " << eff << "\n";
  const SolverSummary& sol = s.solver;
  os << "  " << sol.integrator << " rtol " << sol.rtol << ": " << sol.stats.steps << " steps, " << sol.stats.rhs_evals << " rhs evals, "
     << sol.stats.root_events << " events, " << sol.stats.error_test_fails << " error-test fails; " << std::setprecision(3)
     << s.wall_time_s * 1e3 << " ms";
  if (s.flow) os << " in all, " << s.flow->stats.ode_seconds * 1e3 << " ms of it in " << sol.integrator;
  os << "\n";
  if (const auto kernel = s.model_choice("history.kernel")) {
    os << "  history: " << *kernel << " kernel, " << s.model_choice("history.evaluator").value_or("") << " evaluator";
    if (s.history_modes) os << ", " << *s.history_modes << " modes";
    os << "; peak |f_H| = " << num(s.max_history_force_N) << " N; " << sol.stats.linear_solver << " linear solver, state size "
       << sol.stats.state_size << "\n";
  }
  if (s.flow) {
    const FlowSummary& f = *s.flow;
    os << "  flow: " << f.stats.cells_per_diameter << " cells/D, " << f.stats.levels << " levels, " << f.stats.steps << " flow steps of "
       << std::setprecision(3) << 1e3 * f.stats.dt << " ms, " << f.ms_per_step << " ms per step, " << f.krylov_iterations_per_step
       << " GMRES iterations per step; of the wall time " << std::setprecision(2) << 100 * f.flow_share << " % in the flow kernel, "
       << 100 * f.stats.pre_seconds / s.wall_time_s << " % in its start-up (" << f.stats.pre_steps << " steps, " << f.start << ")\n";
  }
  if (s.bounces_mode == "all" && !s.bounces.empty()) {
    os << "  bounces: contact   t_contact (s)   impact (m/s)   e       apex gap (mm)   t_apex (s)\n";
    for (const BounceSummary& b : s.bounces)
      os << "           " << std::setw(7) << b.contact << "   " << std::setw(13) << num(b.t_contact_s, 5) << "   " << std::setw(12)
         << num(b.impact_velocity_m_s) << "   " << std::setw(5) << num(b.e, 3) << "   " << std::setw(13)
         << (b.apex_gap_m ? num(1e3 * *b.apex_gap_m) : "n/a") << "   " << num(b.t_apex_s, 5) << "\n";
  }
  for (const auto& w : s.warnings) os << "  warning: " << w << "\n";
  return os.str();
}

}  // namespace imcol::run
