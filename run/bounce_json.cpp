// SPDX-License-Identifier: BSD-3-Clause
#include "run/bounce_json.hpp"

#include <stdexcept>

namespace imcol::run {

namespace {

BudgetPhase budget_phase(const std::string& s) {
  for (BudgetPhase p : {BudgetPhase::approach, BudgetPhase::contact, BudgetPhase::rebound, BudgetPhase::collision})
    if (s == to_string(p)) return p;
  throw std::invalid_argument("unknown energy budget phase: " + s);
}

/// One number per force, by name, in kAllForceKinds' order.
Json by_force(const std::array<double, model::kForceKinds>& v) {
  Json j = Json::object();
  for (std::size_t k = 0; k < model::kForceKinds; ++k) j[model::to_string(model::kAllForceKinds[k])] = v[k];
  return j;
}

std::array<double, model::kForceKinds> by_force(const Json& j) {
  std::array<double, model::kForceKinds> v{};
  for (std::size_t k = 0; k < model::kForceKinds; ++k) v[k] = j.at(model::to_string(model::kAllForceKinds[k])).get<double>();
  return v;
}

Json position_or_null(const std::optional<FittedPosition>& p) { return p ? Json(*p) : Json(nullptr); }

/// The fields every measure may write after its e, in summary.json's order.
void put_details(Json& j, const MeasureResult& m) {
  put_if(j, "gap_m", m.gap_m);
  put_if(j, "distance_m", m.distance_m);
  put_if(j, "approach_distance_m", m.approach_distance_m);
  put_if(j, "rebound_distance_m", m.rebound_distance_m);
  put_if(j, "window_s", m.window_s);
  put_if(j, "shortened_from_s", m.shortened_from_s);
  put_if(j, "shortened_by", m.shortened_by);
  put_if(j, "cut_by_end_of_run", m.cut_by_end_of_run);
  if (m.end_mismatch) j["end_mismatch"] = {{"approach", or_null(m.end_mismatch->approach)}, {"rebound", or_null(m.end_mismatch->rebound)}};
  put_if(j, "warning", m.warning);
  put_if(j, "impact_speed_m_s", m.impact_speed_m_s);
  put_if(j, "rebound_speed_m_s", m.rebound_speed_m_s);
  if (m.stretches) {
    j["approach"] = stretch_or_null(m.approach);
    j["rebound"] = stretch_or_null(m.rebound);
  }
  put_if(j, "missing", m.missing);
  put_if(j, "reference", m.reference);
}

void get_details(const Json& j, MeasureResult& m) {
  m.gap_m = get_opt<double>(j, "gap_m");
  m.distance_m = get_opt<double>(j, "distance_m");
  m.approach_distance_m = get_opt<double>(j, "approach_distance_m");
  m.rebound_distance_m = get_opt<double>(j, "rebound_distance_m");
  m.window_s = get_opt<double>(j, "window_s");
  m.shortened_from_s = get_opt<double>(j, "shortened_from_s");
  m.shortened_by = get_opt<std::string>(j, "shortened_by");
  m.cut_by_end_of_run = get_opt<bool>(j, "cut_by_end_of_run");
  if (j.contains("end_mismatch"))
    m.end_mismatch = EndMismatch{get_opt<double>(j["end_mismatch"], "approach"), get_opt<double>(j["end_mismatch"], "rebound")};
  m.warning = get_opt<std::string>(j, "warning");
  m.impact_speed_m_s = get_opt<double>(j, "impact_speed_m_s");
  m.rebound_speed_m_s = get_opt<double>(j, "rebound_speed_m_s");
  m.stretches = j.contains("approach");
  m.approach = get_opt<FittedStretch>(j, "approach");
  m.rebound = get_opt<FittedStretch>(j, "rebound");
  m.missing = get_opt<std::string>(j, "missing");
  m.reference = get_opt<std::string>(j, "reference");
}

}  // namespace

const char* to_string(BudgetPhase p) {
  switch (p) {
    case BudgetPhase::approach: return "approach";
    case BudgetPhase::contact: return "contact";
    case BudgetPhase::rebound: return "rebound";
    case BudgetPhase::collision: return "collision";
  }
  return "";
}

const MeasureResult* Bounce::measure(EMeasure m) const {
  for (const auto& [k, v] : e_measures)
    if (k == m) return &v;
  return nullptr;
}

Json stretch_or_null(const std::optional<FittedStretch>& s) { return s ? Json(*s) : Json(nullptr); }

void to_json(Json& j, const FittedPosition& p) {
  j = {{"t_ref_s", p.t_ref_s}, {"z_m", p.z_m}, {"u_m_s", p.u_m_s}, {"a_m_s2", p.a_m_s2}};
}

void from_json(const Json& j, FittedPosition& p) {
  p = {j.at("t_ref_s").get<double>(), j.at("z_m").get<double>(), j.at("u_m_s").get<double>(), j.at("a_m_s2").get<double>()};
}

void to_json(Json& j, const FittedStretch& s) {
  j = {{"t0_s", s.t0_s}, {"t1_s", s.t1_s}, {"z1", position_or_null(s.z1)}};
  if (s.pair) j["z2"] = position_or_null(s.z2);
}

void from_json(const Json& j, FittedStretch& s) {
  s.t0_s = j.at("t0_s").get<double>();
  s.t1_s = j.at("t1_s").get<double>();
  s.z1 = get_opt<FittedPosition>(j, "z1");
  s.pair = j.contains("z2");
  s.z2 = get_opt<FittedPosition>(j, "z2");
}

void to_json(Json& j, const MeasureResult& m) {
  j = Json::object();
  if (m.velocities) {
    j["impact_velocity_m_s"] = or_null(m.impact_velocity_m_s);
    j["rebound_velocity_m_s"] = or_null(m.rebound_velocity_m_s);
  }
  j["e"] = or_null(m.e);
  put_if(j, "e_raw", m.e_raw);
  put_if(j, "note", m.note);
  put_details(j, m);
}

void from_json(const Json& j, MeasureResult& m) {
  m.velocities = j.contains("impact_velocity_m_s");
  m.impact_velocity_m_s = get_opt<double>(j, "impact_velocity_m_s");
  m.rebound_velocity_m_s = get_opt<double>(j, "rebound_velocity_m_s");
  m.e = get_opt<double>(j, "e");
  m.e_raw = get_opt<double>(j, "e_raw");
  m.note = get_opt<std::string>(j, "note");
  get_details(j, m);
}

void to_json(Json& j, const EnergyPhase& p) {
  j = {{"phase", to_string(p.phase)},
       {"t0_s", p.t0_s},
       {"t1_s", p.t1_s},
       {"kinetic_energy_J", {{"spheres", p.ke_spheres_J}, {"added_mass", p.ke_added_J}}},
       {"work_J", by_force(p.work_J)},
       {"dissipated_J", by_force(p.dissipated_J)},
       {"dissipated_per_impact_energy", by_force(p.dissipated_per_impact_energy)},
       {"closure_J", p.closure_J},
       {"closure_per_impact_energy", p.closure_per_impact_energy}};
}

void from_json(const Json& j, EnergyPhase& p) {
  p.phase = budget_phase(j.at("phase").get<std::string>());
  p.t0_s = j.at("t0_s").get<double>();
  p.t1_s = j.at("t1_s").get<double>();
  p.ke_spheres_J = j.at("kinetic_energy_J").at("spheres").get<std::array<double, 2>>();
  p.ke_added_J = j.at("kinetic_energy_J").at("added_mass").get<std::array<double, 2>>();
  p.work_J = by_force(j.at("work_J"));
  p.dissipated_J = by_force(j.at("dissipated_J"));
  p.dissipated_per_impact_energy = by_force(j.at("dissipated_per_impact_energy"));
  p.closure_J = j.at("closure_J").get<double>();
  p.closure_per_impact_energy = j.at("closure_per_impact_energy").get<double>();
}

void to_json(Json& j, const EnergyBudget& b) { j = {{"impact_kinetic_energy_J", b.impact_kinetic_energy_J}, {"phases", b.phases}}; }

void from_json(const Json& j, EnergyBudget& b) {
  b.impact_kinetic_energy_J = j.at("impact_kinetic_energy_J").get<double>();
  b.phases = j.at("phases").get<std::vector<EnergyPhase>>();
}

void to_json(Json& j, const Bounce& b) {
  j = {{"contact", b.contact}, {"t_contact_s", b.t_contact_s}, {"t_separation_s", or_null(b.t_separation_s)},
       {"impact_speed_at_delta_ss_m_s", b.impact_speed_at_delta_ss_m_s}, {"e", or_null(b.e)}, {"e_is", to_string(b.e_is)},
       {"impact_velocity_m_s", or_null(b.impact_velocity_m_s)}, {"rebound_velocity_m_s", or_null(b.rebound_velocity_m_s)},
       {"e_instant", or_null(b.e_instant)}, {"apex_gap_m", or_null(b.apex_gap_m)}, {"t_apex_s", or_null(b.t_apex_s)}};
  j["energy_budget"] = b.energy_budget ? Json(*b.energy_budget) : Json(nullptr);
  Json dis = Json::object();
  for (const auto& [label, e] : b.measures_disagree) dis[label] = e;
  j["measures_disagree"] = dis;
  Json em = Json::object();
  for (const auto& [m, r] : b.e_measures) em[to_string(m)] = r;
  j["e_measures"] = em;
}

void from_json(const Json& j, Bounce& b) {
  b.contact = j.at("contact").get<int>();
  b.t_contact_s = j.at("t_contact_s").get<double>();
  b.t_separation_s = get_opt<double>(j, "t_separation_s");
  b.impact_speed_at_delta_ss_m_s = j.at("impact_speed_at_delta_ss_m_s").get<double>();
  b.e = get_opt<double>(j, "e");
  b.e_is = choice_of<EMeasure>(j.at("e_is"));
  b.impact_velocity_m_s = get_opt<double>(j, "impact_velocity_m_s");
  b.rebound_velocity_m_s = get_opt<double>(j, "rebound_velocity_m_s");
  b.e_instant = get_opt<double>(j, "e_instant");
  b.apex_gap_m = get_opt<double>(j, "apex_gap_m");
  b.t_apex_s = get_opt<double>(j, "t_apex_s");
  b.energy_budget = get_opt<EnergyBudget>(j, "energy_budget");
  b.measures_disagree.clear();
  for (const auto& [label, e] : j.at("measures_disagree").items()) b.measures_disagree.push_back({label, e.get<double>()});
  b.e_measures.clear();
  for (const auto& [name, r] : j.at("e_measures").items())
    b.e_measures.push_back({choice_of<EMeasure>(Json(name)), r.get<MeasureResult>()});
}

}  // namespace imcol::run
