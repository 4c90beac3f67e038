// SPDX-License-Identifier: BSD-3-Clause
#include "study/summary_bytes.hpp"

#include "study/json_fields.hpp"

namespace imcol {

namespace {

using study::FieldsIn;
using study::FieldsOut;

template <class IO, class S>
void flow_stats_fields(IO& io, S& s) {
  io("steps", s.steps), io("pre_steps", s.pre_steps), io("dt", s.dt), io("h", s.h), io("nr", s.nr), io("nz", s.nz);
  io("levels", s.levels), io("cells_per_diameter", s.cells_per_diameter), io("flow_seconds", s.flow_seconds);
  io("ode_seconds", s.ode_seconds), io("pre_seconds", s.pre_seconds), io("krylov_iterations", s.krylov_iterations);
  io("max_krylov_iterations", s.max_krylov_iterations), io("max_krylov_residual", s.max_krylov_residual);
  io("max_slip", s.max_slip), io("cfl", s.cfl), io("max_courant", s.max_courant), io("max_energy_ratio", s.max_energy_ratio);
  io("min_gap_clamped_steps", s.min_gap_clamped_steps), io("frame_travel", s.frame_travel), io("bytes", s.bytes);
  io("est_start_up_s", s.est_start_up_s), io("est_blocks_s", s.est_blocks_s), io("est_steps_s", s.est_steps_s);
  io("est_bytes", s.est_bytes), io("field_snapshots", s.field_snapshots), io("fields_seconds", s.fields_seconds);
}

template <class IO, class S>
void fluid_fields(IO& io, S& s) {
  io("density", s.density), io("viscosity", s.viscosity), io("name", s.name), io("mass_fraction", s.mass_fraction);
  io("temperature", s.temperature), io("density_source", s.density_source), io("viscosity_source", s.viscosity_source);
}

template <class IO, class S>
void solver_stats_fields(IO& io, S& s) {
  io("steps", s.steps), io("rhs_evals", s.rhs_evals), io("jac_evals", s.jac_evals), io("nonlin_iters", s.nonlin_iters);
  io("nonlin_conv_fails", s.nonlin_conv_fails), io("error_test_fails", s.error_test_fails), io("root_fn_evals", s.root_fn_evals);
  io("root_events", s.root_events), io("reinits", s.reinits), io("lin_iters", s.lin_iters), io("lin_conv_fails", s.lin_conv_fails);
  io("prec_setups", s.prec_setups), io("prec_solves", s.prec_solves), io("breakpoints", s.breakpoints);
  io("order_caps", s.order_caps), io("linear_solver", s.linear_solver), io("state_size", s.state_size);
}

template <class IO, class S>
void solver_fields(IO& io, S& s) {
  io("integrator", s.integrator), io("rtol", s.rtol), io("atol", s.atol), io("t_final_s", s.t_final_s);
  io("measure_interval_s", s.measure_interval_s), io("measure_samples", s.measure_samples), io("stats", s.stats);
}

template <class IO, class S>
void flow_fields(IO& io, S& s) {
  io("stats", s.stats), io("start", s.start), io("force_in_step", s.force_in_step), io("ms_per_step", s.ms_per_step);
  io("krylov_iterations_per_step", s.krylov_iterations_per_step), io("flow_share", s.flow_share), io("ode_share", s.ode_share);
}

template <class IO, class S>
void contact_fields(IO& io, S& s) {
  io("law", s.law), io("t_contact_s", s.t_contact_s), io("t_separation_s", s.t_separation_s);
  io("impact_speed_m_s", s.impact_speed_m_s), io("law_numbers", s.law_numbers), io("e_dry", s.e_dry), io("delta_ss_m", s.delta_ss_m);
}

template <class IO, class S>
void bounce_fields(IO& io, S& s) {
  io("contact", s.contact), io("t_contact_s", s.t_contact_s), io("t_separation_s", s.t_separation_s), io("e", s.e);
  io("impact_velocity_m_s", s.impact_velocity_m_s), io("rebound_velocity_m_s", s.rebound_velocity_m_s);
  io("e_instant", s.e_instant), io("apex_gap_m", s.apex_gap_m), io("t_apex_s", s.t_apex_s);
}

/// e, its measures and the bounces.
template <class IO, class S>
void summary_e_fields(IO& io, S& s) {
  io("e", s.e), io("e_is", s.e_is), io("e_missing", s.e_missing), io("e_fit_raw", s.e_fit_raw), io("e_instant", s.e_instant);
  io("e_instant_gap_m", s.e_instant_gap_m), io("e_measures", s.e_measures), io("e_by_measure", s.e_by_measure);
  io("dissipated_share", s.dissipated_share), io("energy_closure", s.energy_closure);
  io("measures_disagree", s.measures_disagree), io("bounces_mode", s.bounces_mode), io("bounces", s.bounces);
}

/// The dimensionless numbers and how the run went.
template <class IO, class S>
void summary_run_fields(IO& io, S& s) {
  io("St", s.St), io("St_B_table_6_1", s.St_B_table_6_1), io("St_B_eq_6_2", s.St_B_eq_6_2), io("St_L", s.St_L);
  io("St_initial", s.St_initial), io("Re", s.Re), io("St_convention", s.St_convention), io("separated", s.separated);
  io("t_end_too_short", s.t_end_too_short), io("at_rest_since_s", s.at_rest_since_s), io("final_phase", s.final_phase);
  io("contacts", s.contacts), io("U_i1", s.U_i1), io("U_i2", s.U_i2), io("U_r1", s.U_r1), io("U_r2", s.U_r2);
  io("fit_window_s", s.fit_window_s), io("min_gap_m", s.min_gap_m), io("max_contact_force_N", s.max_contact_force_N);
  io("max_history_force_N", s.max_history_force_N), io("group_velocity_m_s", s.group_velocity_m_s);
  io("group_velocity_at_s", s.group_velocity_at_s), io("u1_final_m_s", s.u1_final_m_s), io("u2_final_m_s", s.u2_final_m_s);
  io("contact", s.contact);
}

template <class IO, class S>
void summary_fields(IO& io, S& s) {
  io("scene", s.scene), io("scene_file", s.scene_file), io("configuration", s.configuration), io("fluid", s.fluid);
  summary_e_fields(io, s);
  summary_run_fields(io, s);
  io("effects", s.effects), io("model", s.model), io("history_modes", s.history_modes), io("solver", s.solver);
  io("flow", s.flow), io("warnings", s.warnings), io("wall_time_s", s.wall_time_s), io("setup_time_s", s.setup_time_s);
}

}  // namespace

namespace coupling {
void to_json(nlohmann::json& j, const FlowRunStats& s) { FieldsOut io{j}; flow_stats_fields(io, s); }
void from_json(const nlohmann::json& j, FlowRunStats& s) { FieldsIn io{j}; flow_stats_fields(io, s); }
}  // namespace coupling

void to_json(nlohmann::json& j, const FluidSpec& s) { FieldsOut io{j}; fluid_fields(io, s); }
void from_json(const nlohmann::json& j, FluidSpec& s) { FieldsIn io{j}; fluid_fields(io, s); }
void to_json(nlohmann::json& j, const SolverStats& s) { FieldsOut io{j}; solver_stats_fields(io, s); }
void from_json(const nlohmann::json& j, SolverStats& s) { FieldsIn io{j}; solver_stats_fields(io, s); }
void to_json(nlohmann::json& j, const SolverSummary& s) { FieldsOut io{j}; solver_fields(io, s); }
void from_json(const nlohmann::json& j, SolverSummary& s) { FieldsIn io{j}; solver_fields(io, s); }
void to_json(nlohmann::json& j, const FlowSummary& s) { FieldsOut io{j}; flow_fields(io, s); }
void from_json(const nlohmann::json& j, FlowSummary& s) { FieldsIn io{j}; flow_fields(io, s); }
void to_json(nlohmann::json& j, const ContactSummary& s) { FieldsOut io{j}; contact_fields(io, s); }
void from_json(const nlohmann::json& j, ContactSummary& s) { FieldsIn io{j}; contact_fields(io, s); }
void to_json(nlohmann::json& j, const BounceSummary& s) { FieldsOut io{j}; bounce_fields(io, s); }
void from_json(const nlohmann::json& j, BounceSummary& s) { FieldsIn io{j}; bounce_fields(io, s); }
void to_json(nlohmann::json& j, const RunSummary& s) { FieldsOut io{j}; summary_fields(io, s); }
void from_json(const nlohmann::json& j, RunSummary& s) { FieldsIn io{j}; summary_fields(io, s); }

namespace study {
void to_json(nlohmann::json& j, const SweepPoint& p) {
  FieldsOut io{j};
  io("ok", p.ok), io("value", p.value), io("summary", p.summary), io("message", p.message);
}
void from_json(const nlohmann::json& j, SweepPoint& p) {
  FieldsIn io{j};
  io("ok", p.ok), io("value", p.value), io("summary", p.summary), io("message", p.message);
}
}  // namespace study

}  // namespace imcol
