// SPDX-License-Identifier: BSD-3-Clause
// The typed summary of a run (RunSummary) against summary.json: every typed field has the value written under its
// name, and summary.json read back into the types and written again gives the same bytes (the types carry all of
// it), on scenes that cover each configuration, the bounces, the history force, a start in contact and a coupled run.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/materials.hpp"
#include "run/simulate.hpp"
#include "run/summary_json.hpp"

using namespace imcol;
using Json = nlohmann::ordered_json;

namespace {

/// An optional value against a JSON value that is absent or null exactly when the optional is empty.
void expect_same(const Json& j, const char* key, const std::optional<double>& v) {
  SCOPED_TRACE(key);
  const bool missing = !j.contains(key) || j[key].is_null();
  ASSERT_EQ(missing, !v || !std::isfinite(*v));
  if (!missing) {
    EXPECT_EQ(j[key].get<double>(), *v);
  }
}

void expect_same(const Json& j, const char* key, double v) { expect_same(j, key, std::optional<double>(v)); }

void check(const RunResult& r) {
  const RunSummary& s = r.summary;
  const Json& j = r.summary_json;
  EXPECT_EQ(j["scene"], s.scene);
  EXPECT_EQ(j["scene_file"], s.scene_file);
  EXPECT_EQ(j["configuration"], to_string(s.configuration));
  expect_same(j, "e", s.e);
  EXPECT_EQ(j["e_is"], to_string(s.e_is));
  if (s.e) {
    EXPECT_FALSE(j.contains("e_missing"));
  } else {
    ASSERT_TRUE(j.contains("e_missing"));
    EXPECT_EQ(j["e_missing"].is_null(), !s.e_missing);
    if (s.e_missing) {
      EXPECT_EQ(j["e_missing"], *s.e_missing);
    }
  }
  expect_same(j, "e_fit_raw", s.e_fit_raw);
  expect_same(j, "e_instant", s.e_instant);
  expect_same(j, "e_instant_gap_m", s.e_instant_gap_m);
  // The named measures and the disagreeing ones, in order.
  if (j["e_measures"].is_null()) {
    EXPECT_TRUE(s.e_measures.empty());
  } else {
    ASSERT_EQ(j["e_measures"].size(), s.e_measures.size());
    std::size_t k = 0;
    for (const auto& [name, m] : j["e_measures"].items()) {
      EXPECT_EQ(name, to_string(s.e_measures[k].first));
      expect_same(m, "e", s.e_measures[k].second);
      EXPECT_EQ(s.measure_e(s.e_measures[k].first), s.e_measures[k].second);
      ++k;
    }
    ASSERT_EQ(j["measures_disagree"].size(), s.measures_disagree.size());
    k = 0;
    for (const auto& [name, v] : j["measures_disagree"].items()) {
      EXPECT_EQ(name, s.measures_disagree[k].first);
      EXPECT_EQ(v.get<double>(), s.measures_disagree[k].second);
      ++k;
    }
  }
  EXPECT_EQ(j["bounces_mode"], to_string(s.bounces_mode));
  ASSERT_EQ(j["bounces"].size(), s.bounces.size());
  for (std::size_t k = 0; k < s.bounces.size(); ++k) {
    const Json& b = j["bounces"][k];
    const run::Bounce& x = s.bounces[k];
    EXPECT_EQ(b["contact"].get<int>(), x.contact);
    expect_same(b, "t_contact_s", x.t_contact_s);
    expect_same(b, "t_separation_s", x.t_separation_s);
    expect_same(b, "e", x.e);
    expect_same(b, "impact_velocity_m_s", x.impact_velocity_m_s);
    expect_same(b, "rebound_velocity_m_s", x.rebound_velocity_m_s);
    expect_same(b, "e_instant", x.e_instant);
    expect_same(b, "apex_gap_m", x.apex_gap_m);
    expect_same(b, "t_apex_s", x.t_apex_s);
  }
  expect_same(j, "St", s.St);
  expect_same(j, "St_B_table_6_1", s.St_B_table_6_1);
  expect_same(j, "St_B_eq_6_2", s.St_B_eq_6_2);
  expect_same(j, "St_L", s.St_L);
  expect_same(j, "St_initial", s.St_initial);
  expect_same(j, "Re", s.Re);
  EXPECT_EQ(j["St_convention"], s.St_convention);
  EXPECT_EQ(j["separated"].get<bool>(), s.separated);
  EXPECT_EQ(j["t_end_too_short"].get<bool>(), s.t_end_too_short);
  expect_same(j, "at_rest_since_s", s.at_rest_since_s);
  EXPECT_EQ(j.contains("final_phase"), s.final_phase.has_value());
  if (s.final_phase) {
    EXPECT_EQ(j["final_phase"], *s.final_phase);
  }
  EXPECT_EQ(j["contacts"].get<int>(), s.contacts);
  expect_same(j["velocities_m_s"], "U_i1", s.U_i1);
  expect_same(j["velocities_m_s"], "U_i2", s.U_i2);
  expect_same(j["velocities_m_s"], "U_r1", s.U_r1);
  expect_same(j["velocities_m_s"], "U_r2", s.U_r2);
  expect_same(j, "fit_window_s", s.fit_window_s);
  expect_same(j, "min_gap_m", s.min_gap_m);
  expect_same(j, "max_contact_force_N", s.max_contact_force_N);
  expect_same(j, "max_history_force_N", s.max_history_force_N);
  expect_same(j, "group_velocity_m_s", s.group_velocity_m_s);
  expect_same(j, "group_velocity_at_s", s.group_velocity_at_s);
  expect_same(j, "u1_final_m_s", s.u1_final_m_s);
  expect_same(j, "u2_final_m_s", s.u2_final_m_s);
  ASSERT_EQ(j.contains("contact"), s.contact.has_value());
  if (s.contact) {
    const Json& c = j["contact"];
    EXPECT_EQ(c["law"], to_string(s.contact->law));
    expect_same(c, "t_contact_s", s.contact->t_contact_s);
    expect_same(c, "t_separation_s", s.contact->t_separation_s);
    expect_same(c, "impact_speed_m_s", s.contact->impact_speed_m_s);
    for (const auto& [name, v] : s.contact->law_numbers) expect_same(c, name.c_str(), v);
    expect_same(c, "e_dry", s.contact->e_dry);
    expect_same(c, "delta_ss_m", s.contact->delta_ss_m);
  }
  ASSERT_EQ(j["effects"].size(), s.effects.size());
  for (std::size_t k = 0; k < s.effects.size(); ++k) EXPECT_EQ(j["effects"][k], to_string(s.effects[k]));
  ASSERT_EQ(j["model"].size(), s.model.size());
  for (const auto& [k, v] : s.model) EXPECT_EQ(j["model"][k], v);
  ASSERT_EQ(s.history.has_value(), s.has(Effect::history));
  if (s.history) {
    EXPECT_EQ(j["model"]["history.kernel"], to_string(s.history->kernel));
    EXPECT_EQ(j["model"]["history.evaluator"], to_string(s.history->evaluator));
    EXPECT_EQ(j["model"].contains("history.modes"), s.history->modes.has_value());
    if (s.history->modes) {
      EXPECT_EQ(j["model"]["history.modes"], std::to_string(*s.history->modes));
    }
  }
  const Json& sol = j["solver"];
  EXPECT_EQ(sol["integrator"], to_string(s.solver.integrator));
  expect_same(sol, "rtol", s.solver.rtol);
  expect_same(sol, "atol", s.solver.atol);
  expect_same(sol, "t_final_s", s.solver.t_final_s);
  expect_same(sol, "measure_interval_s", s.solver.measure_interval_s);
  EXPECT_EQ(sol["measure_samples"].get<std::size_t>(), s.solver.measure_samples);
  EXPECT_EQ(sol["linear_solver"], s.solver.stats.linear_solver);
  for (const auto& [k, v] : s.solver.stats.as_map()) EXPECT_EQ(sol[k].get<long>(), v) << k;
  EXPECT_GT(s.solver.stats.steps, 0);
  EXPECT_EQ(j["warnings"], Json(s.warnings));
  ASSERT_EQ(j.contains("flow"), s.flow.has_value());
  if (s.flow) {
    const Json& f = j["flow"];
    EXPECT_EQ(f["steps"].get<long>(), s.flow->stats.steps);
    EXPECT_EQ(f["start_up_steps"].get<long>(), s.flow->stats.pre_steps);
    EXPECT_EQ(f["grid"]["cells_per_diameter"].get<int>(), s.flow->stats.cells_per_diameter);
    EXPECT_EQ(f["grid"]["levels"].get<int>(), s.flow->stats.levels);
    expect_same(f, "dt_s", s.flow->stats.dt);
    expect_same(f, "ms_per_step", s.flow->ms_per_step);
    expect_same(f, "krylov_iterations_per_step", s.flow->krylov_iterations_per_step);
    expect_same(f, "flow_share", s.flow->flow_share);
    expect_same(f, "ode_share", s.flow->ode_share);
    expect_same(f, "start_up_time_s", s.flow->stats.pre_seconds);
    expect_same(f, "ode_time_s", s.flow->stats.ode_seconds);
    EXPECT_EQ(f["start"], to_string(s.flow->start));
    EXPECT_EQ(f["force_in_step"], to_string(s.flow->force_in_step));
  }
  expect_same(j, "wall_time_s", s.wall_time_s);
  expect_same(j, "setup_time_s", s.setup_time_s);
  // Read back into the types and written again: the same bytes, and the same typed values where the run's code reads
  // them (the first contact's views are derived again from the bounces).
  const RunSummary back = j.get<RunSummary>();
  EXPECT_EQ(Json(back).dump(2), j.dump(2));
  EXPECT_EQ(back.e_measures, s.e_measures);
  EXPECT_EQ(back.measures_disagree, s.measures_disagree);
  EXPECT_EQ(back.dissipated_share, s.dissipated_share);
  EXPECT_EQ(back.energy_closure, s.energy_closure);
  EXPECT_EQ(back.effects, s.effects);
  EXPECT_EQ(back.solver.stats.as_map(), s.solver.stats.as_map());
  // As bytes across MPI ranks (CBOR of the same object): every double's bits kept.
  EXPECT_EQ(Json::from_cbor(Json::to_cbor(j)).get<RunSummary>().e, s.e);
  EXPECT_EQ(Json(Json::from_cbor(Json::to_cbor(j)).get<RunSummary>()).dump(), j.dump());
}

RunResult run_scene(const std::string& name, const std::vector<Override>& ov = {}) {
  return simulate(load_scene(data_dir() + "/scenes/" + name, ov));
}

}  // namespace

TEST(RunSummary, AgreesWithSummaryJsonSphereWall) { check(run_scene("default.toml")); }

TEST(RunSummary, AgreesWithSummaryJsonPair) {
  const RunResult r = run_scene("seed_run1.toml");
  EXPECT_EQ(r.summary.configuration, Configuration::sphere_sphere);
  check(r);
}

TEST(RunSummary, AgreesWithSummaryJsonEveryBounce) {
  const RunResult r = run_scene("bouncing_steel.toml");
  EXPECT_GE(r.summary.bounces.size(), 2u);
  check(r);
}

TEST(RunSummary, AgreesWithSummaryJsonFreeSphereWithHistory) {
  const RunResult r = run_scene("rising_sphere.toml");
  EXPECT_EQ(r.summary.configuration, Configuration::free_sphere);
  EXPECT_TRUE(r.summary.max_history_force_N.has_value());
  check(r);
}

TEST(RunSummary, AgreesWithSummaryJsonStartInContact) { check(run_scene("hard/start_inside_contact_zone.toml")); }

TEST(RunSummary, AgreesWithSummaryJsonCoupled) {
  const RunResult r = run_scene("coupled/free_fall_ratio1.2.toml", {{"solver.t_end", "0.6"}});
  ASSERT_TRUE(r.summary.flow.has_value());
  check(r);
}

TEST(RunSummary, KinematicsRecordingHasNoForces) {
  const RunResult r = simulate(load_scene(data_dir() + "/scenes/default.toml"), false, Recording::kinematics);
  EXPECT_FALSE(r.summary.max_contact_force_N);
  check(r);
}
