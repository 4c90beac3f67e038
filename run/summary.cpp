#include "run/summary.hpp"

#include <iomanip>
#include <sstream>

#include "run/json_util.hpp"

namespace imcol::run {

using contact::CollisionModel;

void put_measurements(nlohmann::ordered_json& s, const CollisionModel& model, const Scene& sc, const FirstContact& m,
                      const nlohmann::ordered_json& bounces, const Recorder& rec, const std::vector<std::vector<double>>& rows) {
  const bool pair = model.n_spheres() == 2;
  s["e"] = or_null(m.e);
  s["e_is"] = to_string(sc.measure.e);  // the named measure in e_measures (measure.e; docs/bounces.md)
  if (m.e_fit_raw) s["e_fit_raw"] = *m.e_fit_raw;
  if (!m.e) s["e_missing"] = m.e_missing ? nlohmann::ordered_json(*m.e_missing) : nlohmann::ordered_json(nullptr);
  s["e_instant"] = or_null(m.e_instant);
  s["e_instant_gap_m"] = sc.measure.instant_gap * 2 * model.radius(0);
  // The named measures of the first contact (each contact's are in `bounces`).
  if (!bounces.empty()) {
    s["e_measures"] = bounces[0]["e_measures"];
    s["measures_disagree"] = bounces[0]["measures_disagree"];
  } else {
    s["e_measures"] = nullptr;
  }
  s["bounces_mode"] = to_string(sc.measure.bounces);
  s["bounces"] = bounces;
  s["St"] = or_null(m.St);
  if (pair) {
    // Both conventions, named (docs/model-notes.md): `St` is St_B_table_6_1.
    s["St_convention"] = "St_B_table_6_1: seed Table 6.1, half of eq. (6.2); (1/9)(rho_harm/rho_f) Re_rel for equal spheres";
    s["St_B_table_6_1"] = or_null(m.St);
    s["St_B_eq_6_2"] = or_null(m.St_62);
  } else {
    s["St_convention"] = "m U / (6 pi mu a^2)";
    // Legendre, Zenit, Daniel & Guiraud (2006): the particle's inertia with half the displaced fluid's,
    // St_L = (rho_p + rho_f/2) U d / (9 mu), the variable of their correlation e/e_dry = exp(-35/St_L).
    if (m.St && sc.fluid && model.has_target())
      s["St_L"] = *m.St * (1 + 0.5 * model.fluid_mass(0) / model.mass(0));
    else
      s["St_L"] = nullptr;
  }
  s["Re"] = or_null(m.Re);
  if (sc.fluid && model.has_target()) s["St_initial"] = stokes_numbers(model, sc, model.initial_u_rel()).first;  // nominal, same convention
  s["separated"] = m.separated;
  // The run ended because the pair came to rest (MODEL.md §3 has no event for it; see CollisionModel::observe).
  s["at_rest_since_s"] = or_null(model.t_at_rest());
  s["t_end_too_short"] = m.t_end_too_short;
  if (model.has_target()) s["final_phase"] = contact::to_string(model.phase());
  s["contacts"] = model.contacts();
  s["velocities_m_s"] = {{"U_i1", or_null(m.u_i1)}, {"U_i2", or_null(m.u_i2)}, {"U_r1", or_null(m.u_r1)}, {"U_r2", or_null(m.u_r2)}};
  s["fit_window_s"] = m.fit_window;
  s["min_gap_m"] = model.has_target() ? nlohmann::ordered_json(rec.min_gap()) : nlohmann::ordered_json(nullptr);
  s["max_contact_force_N"] = rec.forces() ? nlohmann::ordered_json(rec.max_contact_force()) : nlohmann::ordered_json(nullptr);
  s["group_velocity_m_s"] = or_null(m.group_velocity);
  if (m.group_velocity) s["group_velocity_at_s"] = *m.t_group;
  if (sc.has(Effect::history))  // at the output samples and events
    s["max_history_force_N"] = rec.forces() ? nlohmann::ordered_json(rec.max_history_force()) : nlohmann::ordered_json(nullptr);
  if (!rows.empty()) {
    s["u1_final_m_s"] = rows.back()[2];
    if (pair) s["u2_final_m_s"] = rows.back()[5];
  }
}

nlohmann::ordered_json contact_block(const CollisionModel& model) {
  const contact::ContactLaw& law = *model.contact_law();
  nlohmann::ordered_json c = {{"law", to_string(law.kind())},
                              {"t_contact_s", or_null(model.t_contact())},
                              {"t_separation_s", or_null(model.t_separation())},
                              {"impact_speed_m_s", model.t_contact() ? nlohmann::ordered_json(model.impact_speed()) : nullptr}};
  for (const auto& v : law.summary()) c[v.name] = or_null(v.value);  // the law's own numbers
  c["e_dry"] = model.e_dry();
  c["delta_ss_m"] = model.delta_ss_m();
  return c;
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

nlohmann::ordered_json flow_block(const coupling::FlowRunStats& fs, const Scene& sc, double wall) {
  const double ms = fs.steps ? 1e3 * fs.flow_seconds / fs.steps : 0.0;
  return {{"grid", {{"cells_per_diameter", fs.cells_per_diameter}, {"h_m", fs.h}, {"nr", fs.nr}, {"nz", fs.nz},
                    {"levels", fs.levels}, {"memory_MB", fs.bytes / 1e6}}},
          {"dt_s", fs.dt}, {"cfl", fs.cfl}, {"max_courant", fs.max_courant}, {"max_energy_ratio", fs.max_energy_ratio}, {"start", to_string(sc.flow.start)}, {"start_up_steps", fs.pre_steps},
          {"force_in_step", to_string(sc.flow.force_in_step)}, {"steps", fs.steps}, {"ms_per_step", ms},
          {"krylov_iterations", fs.krylov_iterations},
          {"krylov_iterations_per_step", fs.steps ? double(fs.krylov_iterations) / fs.steps : 0.0},
          {"max_krylov_iterations", fs.max_krylov_iterations}, {"max_krylov_residual", fs.max_krylov_residual},
          {"max_slip_m_s", fs.max_slip}, {"min_gap_clamped_steps", fs.min_gap_clamped_steps},
          {"frame_travel_m", fs.frame_travel}, {"start_up_time_s", fs.pre_seconds},
          {"flow_time_s", fs.flow_seconds}, {"ode_time_s", fs.ode_seconds},
          {"flow_share", wall > 0 ? fs.flow_seconds / wall : 0.0}, {"ode_share", wall > 0 ? fs.ode_seconds / wall : 0.0},
          {"estimate", {{"start_up_s", fs.est_start_up_s}, {"force_system_blocks_s", fs.est_blocks_s}, {"steps_to_t_end_s", fs.est_steps_s},
                        {"total_s", fs.est_total_s()}, {"memory_MB", fs.est_bytes / 1e6}}}};
}

std::string human_summary(const nlohmann::ordered_json& s) {
  std::ostringstream os;
  auto num = [](const nlohmann::ordered_json& j, int prec = 4) {
    if (j.is_null()) return std::string("n/a");
    std::ostringstream o;
    o << std::setprecision(prec) << j.get<double>();
    return o.str();
  };
  os << "scene " << s["scene"].get<std::string>() << " (" << s["configuration"].get<std::string>() << ")\n";
  os << "  e = " << num(s["e"]) << "   e_instant = " << num(s["e_instant"]) << "   St = " << num(s["St"]);
  if (s.contains("St_B_eq_6_2")) os << " (St_B, Table 6.1; eq. 6.2: " << num(s["St_B_eq_6_2"]) << ")";
  os << "   Re = " << num(s["Re"]) << "\n";
  if (!s["group_velocity_m_s"].is_null())
    os << "  group velocity = " << num(s["group_velocity_m_s"]) << " m/s (no separation; centre-of-mass velocity at t = "
       << num(s["group_velocity_at_s"]) << " s, when the relative velocity vanished)\n";
  if (!s["at_rest_since_s"].is_null())
    os << "  at rest from t = " << num(s["at_rest_since_s"]) << " s (|U_rel| and |dU_rel/dt| x measure.window below stall_fraction x the"
       << " impact speed for one window): the run ended there\n";
  if (!s["min_gap_m"].is_null()) os << "  min gap = " << num(s["min_gap_m"]) << " m, max contact force = " << num(s["max_contact_force_N"]) << " N\n";
  std::string eff;
  for (const auto& x : s["effects"]) eff += (eff.empty() ? "" : ", ") + x.get<std::string>();
  os << "  effects: " << eff << "\n";
  const auto& sol = s["solver"];
  os << "  " << sol["integrator"].get<std::string>() << " rtol " << sol["rtol"].get<double>() << ": "
     << sol["steps"].get<long>() << " steps, " << sol["rhs_evals"].get<long>() << " rhs evals, "
     << sol["root_events"].get<long>() << " events, " << sol["error_test_fails"].get<long>() << " error-test fails; "
     << std::setprecision(3) << s["wall_time_s"].get<double>() * 1e3 << " ms";
  if (s.contains("flow")) os << " in all, " << s["flow"]["ode_time_s"].get<double>() * 1e3 << " ms of it in " << sol["integrator"].get<std::string>();
  os << "\n";
  const auto& mod = s["model"];
  if (mod.contains("history.kernel")) {
    os << "  history: " << mod["history.kernel"].get<std::string>() << " kernel, " << mod["history.evaluator"].get<std::string>()
       << " evaluator";
    if (mod.contains("history.modes")) os << ", " << mod["history.modes"].get<std::string>() << " modes";
    os << "; peak |f_H| = " << num(s["max_history_force_N"]) << " N; " << sol["linear_solver"].get<std::string>()
       << " linear solver, state size " << sol["state_size"].get<long>() << "\n";
  }
  if (s.contains("flow")) {
    const auto& f = s["flow"];
    os << "  flow: " << f["grid"]["cells_per_diameter"].get<int>() << " cells/D, " << f["grid"]["levels"].get<int>() << " levels, "
       << f["steps"].get<long>() << " flow steps of " << std::setprecision(3) << 1e3 * f["dt_s"].get<double>() << " ms, "
       << f["ms_per_step"].get<double>() << " ms per step, " << f["krylov_iterations_per_step"].get<double>()
       << " GMRES iterations per step; of the wall time " << std::setprecision(2) << 100 * f["flow_share"].get<double>()
       << " % in the flow kernel, " << 100 * f["start_up_time_s"].get<double>() / s["wall_time_s"].get<double>()
       << " % in its start-up (" << f["start_up_steps"].get<long>() << " steps, " << f["start"].get<std::string>() << ")\n";
  }
  if (s.contains("bounces_mode") && s["bounces_mode"] == "all" && !s["bounces"].empty()) {
    os << "  bounces: contact   t_contact (s)   impact (m/s)   e       apex gap (mm)   t_apex (s)\n";
    for (const auto& b : s["bounces"])
      os << "           " << std::setw(7) << b["contact"].get<int>() << "   " << std::setw(13) << num(b["t_contact_s"], 5) << "   "
         << std::setw(12) << num(b["impact_velocity_m_s"]) << "   " << std::setw(5) << num(b["e"], 3) << "   " << std::setw(13)
         << (b["apex_gap_m"].is_null() ? "n/a" : num(nlohmann::ordered_json(1e3 * b["apex_gap_m"].get<double>()))) << "   "
         << num(b["t_apex_s"], 5) << "\n";
  }
  for (const auto& w : s["warnings"]) os << "  warning: " << w.get<std::string>() << "\n";
  return os.str();
}

}  // namespace imcol::run
