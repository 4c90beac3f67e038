// SPDX-License-Identifier: BSD-3-Clause
#include "run/summary.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>


namespace imcol::run {

using model::CollisionModel;


void measure_summary(RunSummary& s, const CollisionModel& model, const Watch& watch, const Scene& sc, const FirstContact& m,
                     std::vector<Bounce> bounces, const Recorder& rec, const std::vector<std::vector<double>>& rows) {
  const bool pair = model.n_spheres() == 2;
  s.e = m.e;
  s.e_is = sc.measure.e;  // the named measure in e_measures (measure.e; docs/bounces.md)
  s.e_fit_raw = m.e_fit_raw;
  if (!m.e) s.e_missing = m.e_missing;
  s.e_by_measure = m.e_by_measure;
  s.e_instant = m.e_instant;
  s.e_instant_gap_m = sc.measure.instant_gap * 2 * model.radius(0);
  s.bounces_mode = sc.measure.bounces;
  s.bounces = std::move(bounces);
  first_contact_views(s);  // the first contact's named measures (each contact's are in `bounces`)
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

ContactSummary contact_summary(const CollisionModel& model) {
  const contact::ContactLaw& law = *model.contact_law();
  ContactSummary c;
  c.law = law.kind();
  c.t_contact_s = model.t_contact();
  c.t_separation_s = model.t_separation();
  if (model.t_contact()) c.impact_speed_m_s = model.impact_speed();
  for (const auto& v : law.summary()) c.law_numbers.push_back({v.name, v.value});  // the law's own numbers
  c.e_dry = model.e_dry();
  c.delta_ss_m = model.delta_ss_m();
  return c;
}

FlowSummary flow_summary(const coupling::FlowRunStats& fs, const Scene& sc, double wall) {
  FlowSummary f;
  f.stats = fs;
  f.start = sc.flow.start;
  f.force_in_step = sc.flow.force_in_step;
  f.ms_per_step = fs.steps ? 1e3 * fs.flow_seconds / fs.steps : 0.0;
  f.krylov_iterations_per_step = fs.steps ? double(fs.krylov_iterations) / fs.steps : 0.0;
  f.flow_share = wall > 0 ? fs.flow_seconds / wall : 0.0;
  f.ode_share = wall > 0 ? fs.ode_seconds / wall : 0.0;
  return f;
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

/// "flow: 16 cells/D, 4 levels, 3316 flow steps of 0.09–3.39 ms (adaptive, …), … in its start-up (106 steps, developed)"
std::string flow_line(const FlowSummary& f, double wall_time_s) {
  std::ostringstream os;
  os << "flow: " << f.stats.cells_per_diameter << " cells/D, " << f.stats.levels << " levels, " << f.stats.steps << " flow steps of "
     << std::setprecision(3) << 1e3 * f.stats.dt_min;
  if (f.stats.dt_max > f.stats.dt_min)
    os << "–" << 1e3 * f.stats.dt_max << " ms (adaptive, " << f.stats.step_changes << " changes, first " << 1e3 * f.stats.dt << " ms)";
  else os << " ms";
  os << ", " << f.ms_per_step << " ms per step, " << f.krylov_iterations_per_step << " GMRES iterations per step; of the wall time "
     << std::setprecision(2) << 100 * f.flow_share << " % in the flow kernel, " << 100 * f.stats.pre_seconds / wall_time_s
     << " % in its start-up (" << f.stats.pre_steps << " steps, " << to_string(f.start) << ")";
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
  os << "  e = " << num(s.e) << " (" << to_string(s.e_is) << ")   e_instant = " << num(s.e_instant) << "   St = " << num(s.St);
  if (s.configuration == Configuration::sphere_sphere) os << " (St_B, Table 6.1; eq. 6.2: " << num(s.St_B_eq_6_2) << ")";
  if (s.St_L) os << "   St_L = " << num(s.St_L);
  os << "   Re = " << num(s.Re) << "\n";
  if (s.e_by_measure) os << "  e by measure: " << *s.e_by_measure << "\n";
  if (!s.dissipated_share.empty()) {
    os << "  of the impact kinetic energy, dissipated over the collision by:" << std::fixed << std::setprecision(3);
    for (const auto& [force, d] : s.dissipated_share) os << " " << model::to_string(force) << " " << d;
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
  for (const auto& x : s.effects) eff += (eff.empty() ? "" : ", ") + std::string(to_string(x));
  os << "  effects: " << eff << "\n";
  const SolverSummary& sol = s.solver;
  os << "  " << to_string(sol.integrator) << " rtol " << sol.rtol << ": " << sol.stats.steps << " steps, " << sol.stats.rhs_evals << " rhs evals, "
     << sol.stats.root_events << " events, " << sol.stats.error_test_fails << " error-test fails; " << std::setprecision(3)
     << s.wall_time_s * 1e3 << " ms";
  if (s.flow) os << " in all, " << s.flow->stats.ode_seconds * 1e3 << " ms of it in " << to_string(sol.integrator);
  os << "\n";
  if (s.history) {
    os << "  history: " << to_string(s.history->kernel) << " kernel, " << to_string(s.history->evaluator) << " evaluator";
    if (s.history->modes) os << ", " << *s.history->modes << " modes";
    os << "; peak |f_H| = " << num(s.max_history_force_N) << " N; " << sol.stats.linear_solver << " linear solver, state size "
       << sol.stats.state_size << "\n";
  }
  if (s.flow) os << "  " << flow_line(*s.flow, s.wall_time_s) << "\n";
  if (s.bounces_mode == BouncesMode::all && !s.bounces.empty()) {
    os << "  bounces: contact   t_contact (s)   impact (m/s)   e       apex gap (mm)   t_apex (s)\n";
    for (const Bounce& b : s.bounces)
      os << "           " << std::setw(7) << b.contact << "   " << std::setw(13) << num(b.t_contact_s, 5) << "   " << std::setw(12)
         << num(b.impact_velocity_m_s) << "   " << std::setw(5) << num(b.e, 3) << "   " << std::setw(13)
         << (b.apex_gap_m ? num(1e3 * *b.apex_gap_m) : "n/a") << "   " << num(b.t_apex_s, 5) << "\n";
  }
  for (const auto& w : s.warnings) os << "  warning: " << w << "\n";
  return os.str();
}

}  // namespace imcol::run
