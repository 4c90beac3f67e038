// SPDX-License-Identifier: BSD-3-Clause
// A flow scene's typed result (run/flow_run_result.hpp) against summary.json as run/flow_run_json.hpp writes it, on
// coarse runs of the shipped scenes: the same keys in summary.json's order, every value the typed one (a NaN: null).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "flow/flow_scene.hpp"
#include "run/flow_run.hpp"
#include "run/flow_run_json.hpp"

namespace {

using FlowJson = nlohmann::ordered_json;

imcol::FlowRunResult coarse_flow_run(const std::string& name, int cells, std::optional<double> t_end = std::nullopt) {
  imcol::FlowRunOptions o;
  o.quiet = true;
  o.cells_per_diameter = cells;
  o.t_end = t_end;
  return imcol::run_flow_scene(imcol::flow::load_flow_scene(std::string(IMCOL_DATA_DIR) + "/scenes/flow/" + name + ".toml"), o);
}

/// summary.json as written and read back (NaN written as null).
FlowJson written_flow_summary(const imcol::FlowRunResult& r) { return FlowJson::parse(imcol::flow_summary_json(r).dump(2)); }

void expect_flow_number(const FlowJson& j, const char* key, double v) {
  ASSERT_TRUE(j.contains(key)) << key;
  if (std::isnan(v)) {
    EXPECT_TRUE(j[key].is_null()) << key;
  } else {
    ASSERT_TRUE(j[key].is_number()) << key;
    EXPECT_EQ(j[key].get<double>(), v) << key;
  }
}

void expect_flow_optional(const FlowJson& j, const char* key, const std::optional<double>& v) {
  ASSERT_TRUE(j.contains(key)) << key;
  if (v) expect_flow_number(j, key, *v);
  else EXPECT_TRUE(j[key].is_null()) << key;
}

std::vector<std::string> flow_keys(const FlowJson& j) {
  std::vector<std::string> k;
  for (auto it = j.begin(); it != j.end(); ++it) k.push_back(it.key());
  return k;
}

/// summary.json's top-level keys in order, for the parts the result holds.
std::vector<std::string> expected_flow_keys(const imcol::FlowRunResult& r) {
  std::vector<std::string> k = {"scene", "name", "Re", "drag_coefficient", "drag_change_last_tenth_percent", "drag_settled",
                                "drag_left_to_settle_percent", "distance_passed_D", "drag_coefficient_standard", "drag_error_percent",
                                "stokes_drag_ratio"};
  if (r.one_sphere) {
    for (const char* s : {"wake_length_D", "time_to_3pct_s", "wall_time_to_3pct_s"}) k.push_back(s);
    if (r.one_sphere->impulsive_start) k.push_back("impulsive_start");
  }
  k.push_back("forces_N");
  if (r.gap) k.insert(k.end(), {"min_gap_D", "gap_resolved"});
  if (r.gap_forces) k.push_back("f_sim_vs_f_thr");
  if (r.wall) k.push_back("wall");
  if (r.oscillating) k.push_back("oscillating");
  for (const char* s : {"grid", "dt", "theta", "steps", "t_end", "wall_time_s", "ms_per_step", "memory_bytes", "force_solver"}) k.push_back(s);
  return k;
}

void expect_drag_agrees(const FlowJson& j, const imcol::FlowRunResult& r) {
  EXPECT_EQ(j["scene"], r.scene);
  EXPECT_EQ(j["name"], r.name);
  expect_flow_number(j, "Re", r.Re);
  expect_flow_number(j, "drag_coefficient", r.drag.coefficient);
  expect_flow_number(j, "drag_change_last_tenth_percent", r.drag.change_last_tenth_percent);
  EXPECT_EQ(j["drag_settled"].get<bool>(), r.drag.settled);
  expect_flow_number(j, "drag_left_to_settle_percent", r.drag.left_to_settle_percent);
  expect_flow_number(j, "distance_passed_D", r.drag.distance_passed_D);
  expect_flow_optional(j, "drag_coefficient_standard", r.drag.standard);
  expect_flow_optional(j, "drag_error_percent", r.drag.error_percent);
  expect_flow_number(j, "stokes_drag_ratio", r.drag.stokes_drag_ratio);
  ASSERT_EQ(j["forces_N"].size(), r.forces_N.size());
  for (std::size_t b = 0; b < r.forces_N.size(); ++b) EXPECT_EQ(j["forces_N"][b].get<double>(), r.forces_N[b]);
}

void expect_one_sphere_agrees(const FlowJson& j, const imcol::FlowRunResult& r) {
  if (!r.one_sphere) return;
  const auto& s = *r.one_sphere;
  expect_flow_optional(j, "wake_length_D", s.wake_length_D);
  expect_flow_optional(j, "time_to_3pct_s", s.time_to_3pct_s);
  expect_flow_optional(j, "wall_time_to_3pct_s", s.wall_time_to_3pct_s);
  if (!s.impulsive_start) return;
  const FlowJson& b = j["impulsive_start"];
  EXPECT_EQ(b["window_t"][0].get<double>(), s.impulsive_start->window_t0);
  EXPECT_EQ(b["window_t"][1].get<double>(), s.impulsive_start->window_t1);
  expect_flow_number(b, "max_rel_error", s.impulsive_start->max_rel_error);
}

void expect_references_agree(const FlowJson& j, const imcol::FlowRunResult& r) {
  if (r.gap) {
    expect_flow_number(j, "min_gap_D", r.gap->min_gap_D);
    EXPECT_EQ(j["gap_resolved"].get<bool>(), r.gap->resolved);
  }
  if (r.gap_forces) {
    ASSERT_EQ(j["f_sim_vs_f_thr"].size(), r.gap_forces->size());
    for (std::size_t i = 0; i < r.gap_forces->size(); ++i) {
      const FlowJson& row = j["f_sim_vs_f_thr"][i];
      const auto& g = (*r.gap_forces)[i];
      expect_flow_number(row, "gap_D", g.gap_D);
      expect_flow_number(row, "gap_cells", g.gap_cells);
      EXPECT_EQ(row["resolved"].get<bool>(), g.resolved);
      expect_flow_number(row, "F1", g.F1);
      expect_flow_number(row, "F_THR1", g.F_THR1);
      EXPECT_EQ(row.contains("F2"), g.F2.has_value());
      EXPECT_EQ(row.contains("F_wall"), g.F_wall.has_value());
      if (g.F2) expect_flow_number(row, "F2", *g.F2), expect_flow_number(row, "F_THR2", *g.F_THR2);
      if (g.F_wall) expect_flow_number(row, "F_wall", *g.F_wall);
    }
  }
  if (r.wall) {
    expect_flow_number(j["wall"], "position", r.wall->position);
    expect_flow_number(j["wall"], "force_N", r.wall->force_N);
    EXPECT_EQ(j["wall"]["f_thr"].get<std::string>().empty(), !r.wall->brenner);
  }
  if (r.oscillating) {
    expect_flow_number(j["oscillating"], "delta_over_a", r.oscillating->delta_over_a);
    expect_flow_number(j["oscillating"], "max_error_last_period_rel_amplitude", r.oscillating->max_error_rel_amplitude);
  }
}

void expect_grid_and_steps_agree(const FlowJson& j, const imcol::FlowRunResult& r) {
  const FlowJson& g = j["grid"];
  EXPECT_EQ(g["cells_per_diameter"].get<int>(), r.grid.cells_per_diameter);
  expect_flow_number(g, "h", r.grid.h);
  EXPECT_EQ(g["levels"].get<int>(), r.grid.levels);
  EXPECT_EQ(g["nr"].get<int>(), r.grid.nr);
  EXPECT_EQ(g["nz"].get<int>(), r.grid.nz);
  expect_flow_number(g["finest"], "r_max", r.grid.finest.r_max);
  expect_flow_number(g["coarsest"], "z_min", r.grid.coarsest.z_min);
  EXPECT_EQ(g["body_points"].get<std::size_t>(), r.grid.body_points);
  expect_flow_number(j, "dt", r.dt);
  expect_flow_number(j, "theta", r.theta);
  EXPECT_EQ(j["steps"].get<long>(), r.steps);
  expect_flow_number(j, "t_end", r.t_end);
  expect_flow_number(j, "wall_time_s", r.wall_time_s);
  expect_flow_number(j, "ms_per_step", r.ms_per_step);
  EXPECT_EQ(j["memory_bytes"].get<std::size_t>(), r.memory_bytes);
  expect_flow_number(j["force_solver"], "krylov_tol", r.force_solver.krylov_tol);
  expect_flow_number(j["force_solver"], "krylov_iterations_mean", r.force_solver.krylov_iterations_mean);
  EXPECT_EQ(j["force_solver"]["krylov_iterations_max"].get<int>(), r.force_solver.krylov_iterations_max);
  expect_flow_number(j["force_solver"], "max_slip", r.force_solver.max_slip);
}

void expect_flow_summary_agrees(const imcol::FlowRunResult& r) {
  const FlowJson j = written_flow_summary(r);
  EXPECT_EQ(flow_keys(j), expected_flow_keys(r));
  expect_drag_agrees(j, r);
  expect_one_sphere_agrees(j, r);
  expect_references_agree(j, r);
  expect_grid_and_steps_agree(j, r);
}

}  // namespace

TEST(FlowRunResult, ImpulsiveStartAgreesWithSummaryJson) {
  const imcol::FlowRunResult r = coarse_flow_run("impulsive_sphere_re0.1", 8);
  ASSERT_TRUE(r.one_sphere.has_value());
  ASSERT_TRUE(r.one_sphere->impulsive_start.has_value());
  EXPECT_GT(r.steps, 0);
  EXPECT_FALSE(r.gap.has_value());
  expect_flow_summary_agrees(r);
}

TEST(FlowRunResult, SphereAndWallAgreeWithSummaryJson) {
  const imcol::FlowRunResult r = coarse_flow_run("sphere_wall_approach_re0.1", 8);
  ASSERT_TRUE(r.wall.has_value());
  EXPECT_TRUE(r.wall->brenner);
  ASSERT_TRUE(r.gap_forces.has_value());
  ASSERT_FALSE(r.gap_forces->empty());
  EXPECT_TRUE(r.gap_forces->front().F_wall.has_value());
  expect_flow_summary_agrees(r);
}

TEST(FlowRunResult, TwoSpheresAgreeWithSummaryJson) {
  const imcol::FlowRunResult r = coarse_flow_run("two_spheres_approach_re10", 8);
  ASSERT_TRUE(r.gap_forces.has_value());
  ASSERT_FALSE(r.gap_forces->empty());
  EXPECT_TRUE(r.gap_forces->front().F2.has_value());
  EXPECT_FALSE(r.one_sphere.has_value());
  expect_flow_summary_agrees(r);
}

TEST(FlowRunResult, OscillatingSphereAgreesWithSummaryJson) {
  const imcol::FlowRunResult r = coarse_flow_run("oscillating_sphere_re0.3", 8);
  ASSERT_TRUE(r.oscillating.has_value());
  expect_flow_summary_agrees(r);
}
