// SPDX-License-Identifier: BSD-3-Clause
#include "run/summary_json.hpp"

#include <cmath>
#include <stdexcept>

namespace imcol {

using run::choice_of;
using run::get_opt;
using run::Json;
using run::or_null;
using run::put_if;

namespace {

Configuration configuration_of(const std::string& s) {
  for (Configuration c : {Configuration::free_sphere, Configuration::sphere_wall, Configuration::sphere_sphere})
    if (s == to_string(c)) return c;
  throw std::invalid_argument("unknown configuration in a run's summary: " + s);
}

/// e, its measures and the first contact's (summary.json from `e` to `bounces`).
void put_e(Json& j, const RunSummary& s) {
  j["e"] = or_null(s.e);
  j["e_is"] = to_string(s.e_is);
  put_if(j, "e_fit_raw", s.e_fit_raw);
  if (!s.e) j["e_missing"] = or_null(s.e_missing);
  j["e_instant"] = or_null(s.e_instant);
  j["e_instant_gap_m"] = s.e_instant_gap_m;
  if (!s.bounces.empty()) {
    const run::Bounce& b = s.bounces[0];
    Json em = Json::object(), dis = Json::object();
    for (const auto& [m, r] : b.e_measures) em[to_string(m)] = r;
    for (const auto& [label, e] : b.measures_disagree) dis[label] = e;
    j["e_measures"] = em;
    j["measures_disagree"] = dis;
    j["energy_budget"] = b.energy_budget ? Json(*b.energy_budget) : Json(nullptr);
  } else {
    j["e_measures"] = nullptr;
  }
  j["bounces_mode"] = to_string(s.bounces_mode);
  j["bounces"] = s.bounces;
}

/// The dimensionless numbers and how the run went (summary.json from `St` to `u2_final_m_s`).
void put_numbers(Json& j, const RunSummary& s) {
  j["St"] = or_null(s.St);
  j["St_convention"] = s.St_convention;
  if (s.configuration == Configuration::sphere_sphere) {
    j["St_B_table_6_1"] = or_null(s.St_B_table_6_1);
    j["St_B_eq_6_2"] = or_null(s.St_B_eq_6_2);
  } else {
    j["St_L"] = or_null(s.St_L);
  }
  j["Re"] = or_null(s.Re);
  put_if(j, "St_initial", s.St_initial);
  j["separated"] = s.separated;
  j["at_rest_since_s"] = or_null(s.at_rest_since_s);
  j["t_end_too_short"] = s.t_end_too_short;
  put_if(j, "final_phase", s.final_phase);
  j["contacts"] = s.contacts;
  j["velocities_m_s"] = {{"U_i1", or_null(s.U_i1)}, {"U_i2", or_null(s.U_i2)}, {"U_r1", or_null(s.U_r1)}, {"U_r2", or_null(s.U_r2)}};
  j["fit_window_s"] = s.fit_window_s;
  j["min_gap_m"] = or_null(s.min_gap_m);
  j["max_contact_force_N"] = or_null(s.max_contact_force_N);
  j["group_velocity_m_s"] = or_null(s.group_velocity_m_s);
  put_if(j, "group_velocity_at_s", s.group_velocity_at_s);
  if (s.has(Effect::history)) j["max_history_force_N"] = or_null(s.max_history_force_N);
  put_if(j, "u1_final_m_s", s.u1_final_m_s);
  put_if(j, "u2_final_m_s", s.u2_final_m_s);
}

void get_e(const Json& j, RunSummary& s) {
  s.e = get_opt<double>(j, "e");
  s.e_is = choice_of<EMeasure>(j.at("e_is"));
  s.e_fit_raw = get_opt<double>(j, "e_fit_raw");
  s.e_missing = get_opt<std::string>(j, "e_missing");
  s.e_instant = get_opt<double>(j, "e_instant");
  s.e_instant_gap_m = j.at("e_instant_gap_m").get<double>();
  s.bounces_mode = choice_of<BouncesMode>(j.at("bounces_mode"));
  s.bounces = j.at("bounces").get<std::vector<run::Bounce>>();
}

void get_numbers(const Json& j, RunSummary& s) {
  s.St = get_opt<double>(j, "St");
  s.St_convention = j.at("St_convention").get<std::string>();
  s.St_B_table_6_1 = get_opt<double>(j, "St_B_table_6_1");
  s.St_B_eq_6_2 = get_opt<double>(j, "St_B_eq_6_2");
  s.St_L = get_opt<double>(j, "St_L");
  s.Re = get_opt<double>(j, "Re");
  s.St_initial = get_opt<double>(j, "St_initial");
  s.separated = j.at("separated").get<bool>();
  s.at_rest_since_s = get_opt<double>(j, "at_rest_since_s");
  s.t_end_too_short = j.at("t_end_too_short").get<bool>();
  s.final_phase = get_opt<std::string>(j, "final_phase");
  s.contacts = j.at("contacts").get<int>();
  const Json& v = j.at("velocities_m_s");
  s.U_i1 = get_opt<double>(v, "U_i1");
  s.U_i2 = get_opt<double>(v, "U_i2");
  s.U_r1 = get_opt<double>(v, "U_r1");
  s.U_r2 = get_opt<double>(v, "U_r2");
  s.fit_window_s = j.at("fit_window_s").get<double>();
  s.min_gap_m = get_opt<double>(j, "min_gap_m");
  s.max_contact_force_N = get_opt<double>(j, "max_contact_force_N");
  s.group_velocity_m_s = get_opt<double>(j, "group_velocity_m_s");
  s.group_velocity_at_s = get_opt<double>(j, "group_velocity_at_s");
  s.max_history_force_N = get_opt<double>(j, "max_history_force_N");
  s.u1_final_m_s = get_opt<double>(j, "u1_final_m_s");
  s.u2_final_m_s = get_opt<double>(j, "u2_final_m_s");
}

/// The model block's choices, and the history's typed (its kernel, evaluator and modes are model block lines).
void get_model(const Json& j, RunSummary& s) {
  s.effects = effects_of(j.at("effects"));
  s.model.clear();
  for (const auto& [k, v] : j.at("model").items()) s.model.push_back({k, v.get<std::string>()});
  s.history.reset();
  if (!s.has(Effect::history)) return;
  const Json& m = j.at("model");
  HistorySummary h;
  h.kernel = choice_of<KernelKind>(m.at("history.kernel"));
  h.evaluator = choice_of<HistoryEvaluator>(m.at("history.evaluator"));
  if (m.contains("history.modes")) h.modes = std::stol(m.at("history.modes").get<std::string>());
  s.history = h;
}

}  // namespace

void to_json(Json& j, const RunSummary& s) {
  j = {{"scene", s.scene}, {"scene_file", s.scene_file}, {"configuration", to_string(s.configuration)}};
  if (s.fluid) j["fluid"] = *s.fluid;
  put_e(j, s);
  put_numbers(j, s);
  if (s.contact) j["contact"] = *s.contact;
  j["effects"] = effects_to_json(s.effects);
  Json mod = Json::object();
  for (const auto& [k, v] : s.model) mod[k] = v;
  j["model"] = mod;
  j["solver"] = s.solver;
  j["events"] = s.events;
  j["warnings"] = s.warnings;
  if (s.flow) j["flow"] = *s.flow;
  j["wall_time_s"] = s.wall_time_s;
  j["setup_time_s"] = s.setup_time_s;
}

void from_json(const Json& j, RunSummary& s) {
  s = RunSummary{};
  s.scene = j.at("scene").get<std::string>();
  s.scene_file = j.at("scene_file").get<std::string>();
  s.configuration = configuration_of(j.at("configuration").get<std::string>());
  s.fluid = get_opt<FluidSpec>(j, "fluid");
  get_e(j, s);
  get_numbers(j, s);
  s.contact = get_opt<ContactSummary>(j, "contact");
  get_model(j, s);
  s.solver = j.at("solver").get<SolverSummary>();
  s.events = j.at("events").get<std::vector<EventSummary>>();
  s.warnings = j.at("warnings").get<std::vector<std::string>>();
  s.flow = get_opt<FlowSummary>(j, "flow");
  s.wall_time_s = j.at("wall_time_s").get<double>();
  s.setup_time_s = j.at("setup_time_s").get<double>();
  first_contact_views(s);
}

Json effects_to_json(const std::vector<Effect>& effects) {
  Json j = Json::array();
  for (Effect x : effects) j.push_back(to_string(x));
  return j;
}

std::vector<Effect> effects_of(const Json& names) {
  std::vector<Effect> out;
  for (const auto& x : names) {
    const auto e = effect_from_string(x.get<std::string>());
    if (!e) throw std::invalid_argument("unknown effect in a run's summary: " + x.get<std::string>());
    out.push_back(*e);
  }
  return out;
}

void to_json(Json& j, const ContactSummary& c) {
  j = {{"law", to_string(c.law)},
       {"t_contact_s", or_null(c.t_contact_s)},
       {"t_separation_s", or_null(c.t_separation_s)},
       {"impact_speed_m_s", or_null(c.impact_speed_m_s)}};
  for (const auto& [name, v] : c.law_numbers) j[name] = or_null(v);
  j["e_dry"] = c.e_dry;
  j["delta_ss_m"] = c.delta_ss_m;
}

void from_json(const Json& j, ContactSummary& c) {
  c.law = choice_of<ContactLawKind>(j.at("law"));
  c.t_contact_s = get_opt<double>(j, "t_contact_s");
  c.t_separation_s = get_opt<double>(j, "t_separation_s");
  c.impact_speed_m_s = get_opt<double>(j, "impact_speed_m_s");
  c.law_numbers.clear();
  for (const auto& [k, v] : j.items())  // the law's own numbers: between impact_speed_m_s and e_dry
    if (k != "law" && k != "t_contact_s" && k != "t_separation_s" && k != "impact_speed_m_s" && k != "e_dry" && k != "delta_ss_m")
      c.law_numbers.push_back({k, v.is_null() ? std::nullopt : std::optional<double>(v.get<double>())});
  c.e_dry = j.at("e_dry").get<double>();
  c.delta_ss_m = j.at("delta_ss_m").get<double>();
}

void to_json(Json& j, const SolverSummary& s) {
  j = {{"integrator", to_string(s.integrator)}, {"linear_solver", s.stats.linear_solver}, {"rtol", s.rtol}, {"atol", s.atol},
       {"absolute_tolerances", s.absolute_tolerances}, {"state", s.state}, {"max_step_s", s.max_step_s}, {"t_final_s", s.t_final_s}};
  for (const auto& [k, v] : s.stats.as_map()) j[k] = v;
  j["measure_interval_s"] = s.measure_interval_s;
  j["measure_samples"] = s.measure_samples;
}

void from_json(const Json& j, SolverSummary& s) {
  s.integrator = choice_of<IntegratorMethod>(j.at("integrator"));
  s.rtol = j.at("rtol").get<double>();
  s.atol = j.at("atol").get<double>();
  s.absolute_tolerances = j.at("absolute_tolerances").get<std::vector<double>>();
  s.state = j.at("state").get<std::vector<std::string>>();
  s.max_step_s = j.at("max_step_s").get<double>();
  s.t_final_s = j.at("t_final_s").get<double>();
  SolverStats& st = s.stats;
  st.linear_solver = j.at("linear_solver").get<std::string>();
  for (const auto& [name, field] : SolverStats::counters()) st.*field = j.at(name).get<long>();
  st.state_size = j.at("state_size").get<std::size_t>();
  s.measure_interval_s = j.at("measure_interval_s").get<double>();
  s.measure_samples = j.at("measure_samples").get<std::size_t>();
}

void to_json(Json& j, const FluidSpec& f) {
  j["name"] = f.name.empty() ? Json(nullptr) : Json(f.name);
  j["mass_fraction"] = or_null(f.mass_fraction);
  j["temperature_C"] = or_null(f.temperature);
  j["density_kg_m3"] = f.density;
  j["viscosity_Pa_s"] = f.viscosity;
  j["density_source"] = f.density_source;
  j["viscosity_source"] = f.viscosity_source;
}

void from_json(const Json& j, FluidSpec& f) {
  f.name = get_opt<std::string>(j, "name").value_or("");
  f.mass_fraction = get_opt<double>(j, "mass_fraction");
  f.temperature = get_opt<double>(j, "temperature_C");
  f.density = j.at("density_kg_m3").get<double>();
  f.viscosity = j.at("viscosity_Pa_s").get<double>();
  f.density_source = j.at("density_source").get<std::string>();
  f.viscosity_source = j.at("viscosity_source").get<std::string>();
}

void to_json(Json& j, const EventSummary& e) { j = {{"t", e.t_s}, {"event", e.event}, {"gap_m", e.gap_m}, {"u_rel_m_s", e.u_rel_m_s}}; }

void from_json(const Json& j, EventSummary& e) {
  e = {j.at("t").get<double>(), j.at("event").get<std::string>(), j.at("gap_m").get<double>(), j.at("u_rel_m_s").get<double>()};
}

void to_json(Json& j, const FlowSummary& f) {
  const coupling::FlowRunStats& fs = f.stats;
  j = {{"grid", {{"cells_per_diameter", fs.cells_per_diameter}, {"h_m", fs.h}, {"nr", fs.nr}, {"nz", fs.nz},
                 {"levels", fs.levels}, {"memory_MB", fs.bytes / 1e6}}},
       {"dt_s", fs.dt}, {"dt_min_s", fs.dt_min}, {"dt_max_s", fs.dt_max}, {"step_changes", fs.step_changes}, {"cfl", fs.cfl}, {"max_courant", fs.max_courant}, {"max_energy_ratio", fs.max_energy_ratio},
       {"start", to_string(f.start)}, {"start_up_steps", fs.pre_steps}, {"force_in_step", to_string(f.force_in_step)},
       {"steps", fs.steps}, {"ms_per_step", f.ms_per_step}, {"krylov_iterations", fs.krylov_iterations},
       {"krylov_iterations_per_step", f.krylov_iterations_per_step}, {"max_krylov_iterations", fs.max_krylov_iterations},
       {"q_applications", fs.q_applications}, {"start_up_q_applications", fs.pre_q_applications}, {"preconditioner_blocks", fs.preconditioner_blocks},
       {"max_krylov_residual", fs.max_krylov_residual}, {"max_slip_m_s", fs.max_slip},
       {"min_gap_clamped_steps", fs.min_gap_clamped_steps}, {"frame_travel_m", fs.frame_travel},
       {"start_up_time_s", fs.pre_seconds}, {"flow_time_s", fs.flow_seconds}, {"ode_time_s", fs.ode_seconds},
       {"flow_share", f.flow_share}, {"ode_share", f.ode_share}, {"field_snapshots", fs.field_snapshots},
       {"fields_time_s", fs.fields_seconds}, {"cpu_time_s", fs.cpu_seconds},
       {"estimate", {{"start_up_s", fs.est_start_up_s}, {"force_system_blocks_s", fs.est_blocks_s}, {"steps_to_t_end_s", fs.est_steps_s},
                     {"fields_s", fs.est_fields_s}, {"total_s", fs.est_total_s()}, {"memory_MB", fs.est_bytes / 1e6},
                     {"q_applications", fs.est_q_applications}, {"steps", fs.est_steps}, {"field_snapshots", fs.est_field_snapshots}}}};
}

void from_json(const Json& j, FlowSummary& f) {
  coupling::FlowRunStats& fs = f.stats;
  const Json& g = j.at("grid");
  fs.cells_per_diameter = g.at("cells_per_diameter").get<int>();
  fs.h = g.at("h_m").get<double>();
  fs.nr = g.at("nr").get<int>();
  fs.nz = g.at("nz").get<int>();
  fs.levels = g.at("levels").get<int>();
  fs.bytes = static_cast<std::size_t>(std::llround(g.at("memory_MB").get<double>() * 1e6));
  fs.dt = j.at("dt_s").get<double>();
  fs.dt_min = j.value("dt_min_s", fs.dt);  // summaries before 0.15.0: a fixed step
  fs.dt_max = j.value("dt_max_s", fs.dt);
  fs.step_changes = j.value("step_changes", 0L);
  fs.cfl = j.at("cfl").get<double>();
  fs.max_courant = j.at("max_courant").get<double>();
  fs.max_energy_ratio = j.at("max_energy_ratio").get<double>();
  f.start = choice_of<FlowStart>(j.at("start"));
  fs.pre_steps = j.at("start_up_steps").get<long>();
  f.force_in_step = choice_of<ForceInStep>(j.at("force_in_step"));
  fs.steps = j.at("steps").get<long>();
  f.ms_per_step = j.at("ms_per_step").get<double>();
  fs.krylov_iterations = j.at("krylov_iterations").get<long>();
  f.krylov_iterations_per_step = j.at("krylov_iterations_per_step").get<double>();
  fs.max_krylov_iterations = j.at("max_krylov_iterations").get<int>();
  fs.q_applications = j.value("q_applications", 0L);  // summaries before 0.16.0: not counted
  fs.pre_q_applications = j.value("start_up_q_applications", 0L);  // before 0.18.0
  fs.preconditioner_blocks = j.value("preconditioner_blocks", 0L);
  fs.max_krylov_residual = j.at("max_krylov_residual").get<double>();
  fs.max_slip = j.at("max_slip_m_s").get<double>();
  fs.min_gap_clamped_steps = j.at("min_gap_clamped_steps").get<long>();
  fs.frame_travel = j.at("frame_travel_m").get<double>();
  fs.pre_seconds = j.at("start_up_time_s").get<double>();
  fs.flow_seconds = j.at("flow_time_s").get<double>();
  fs.ode_seconds = j.at("ode_time_s").get<double>();
  f.flow_share = j.at("flow_share").get<double>();
  f.ode_share = j.at("ode_share").get<double>();
  fs.field_snapshots = j.at("field_snapshots").get<int>();
  fs.fields_seconds = j.at("fields_time_s").get<double>();
  fs.cpu_seconds = j.at("cpu_time_s").get<double>();
  const Json& est = j.at("estimate");
  fs.est_start_up_s = est.at("start_up_s").get<double>();
  fs.est_blocks_s = est.at("force_system_blocks_s").get<double>();
  fs.est_steps_s = est.at("steps_to_t_end_s").get<double>();
  fs.est_fields_s = est.at("fields_s").get<double>();
  fs.est_bytes = est.at("memory_MB").get<double>() * 1e6;
  fs.est_q_applications = est.value("q_applications", 0.0);  // summaries before 0.18.0: not given
  fs.est_steps = est.value("steps", 0.0);
  fs.est_field_snapshots = est.value("field_snapshots", 0.0);
}

}  // namespace imcol
