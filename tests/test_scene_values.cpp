// SPDX-License-Identifier: BSD-3-Clause
// core/scene_values.hpp: the text the ranks of an MPI job compare changes with every scene key, and only then.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "apps/cluster.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"
#include "core/scene_values.hpp"

namespace {

using imcol::Override;

std::string values_of(const std::string& scene, const std::vector<Override>& ov = {}) {
  return imcol::scene_values(imcol::load_scene(imcol::data_dir() + "/scenes/" + scene + ".toml", ov));
}

/// Each key set to a value the scene does not hold: the text must change, and differ from every other key's.
void expect_every_key_counts(const std::string& scene, const std::vector<Override>& keys) {
  const std::string base = values_of(scene);
  std::set<std::string> seen{base};
  for (const auto& o : keys) {
    std::string changed;
    try {
      changed = values_of(scene, {o});
    } catch (const std::exception& e) {
      ADD_FAILURE() << scene << ": " << o.key << "=" << o.value << " refused: " << e.what();
      continue;
    }
    EXPECT_NE(changed, base) << scene << ": " << o.key << "=" << o.value << " leaves the text unchanged";
    EXPECT_TRUE(seen.insert(changed).second) << scene << ": " << o.key << " gives another key's text";
  }
}

}  // namespace

TEST(SceneValues, EqualScenesGiveEqualTextAndDigest) {
  EXPECT_EQ(values_of("default"), values_of("default"));
  EXPECT_EQ(imcol::cluster::digest(values_of("default")), imcol::cluster::digest(values_of("default")));
  // An override equal to the file's value is the same scene.
  EXPECT_EQ(values_of("default"), values_of("default", {{"fluid.viscosity", "0.02"}}));
  EXPECT_NE(values_of("default"), values_of("gg3462"));
  // The digest is FNV-1a 64: the same on every machine.
  EXPECT_EQ(imcol::cluster::digest(""), 14695981039346656037ull);
  EXPECT_EQ(imcol::cluster::digest("a"), 0xaf63dc4c8601ec8cull);
}

TEST(SceneValues, MaterialsAreTheirResolvedValues) {
  // The material's values are in the text, not only its name: another materials.csv gives another text.
  const std::string t = values_of("default");
  const imcol::Material* steel = imcol::MaterialTable::builtin().find("steel");
  ASSERT_NE(steel, nullptr);
  EXPECT_NE(t.find("sphere.0.density = " + imcol::scene_values_detail::num(steel->density) + "\n"), std::string::npos) << t;
  EXPECT_NE(t.find("sphere.0.youngs_modulus = " + imcol::scene_values_detail::num(steel->youngs_modulus) + "\n"), std::string::npos) << t;
}

TEST(SceneValues, EveryCollisionKeyChangesTheText) {
  expect_every_key_counts(
      "default",
      {{"name", "\"other\""}, {"description", "\"other\""}, {"fluid.density", "1100.0"}, {"fluid.viscosity", "0.03"},
       {"sphere[0].diameter", "0.012"}, {"sphere[0].position", "-0.013"}, {"sphere[0].velocity", "0.31"},
       {"sphere[0].density", "7000.0"}, {"sphere[0].youngs_modulus", "1e11"}, {"sphere[0].poisson_ratio", "0.3"},
       {"sphere[0].e_dry", "0.9"}, {"wall.position", "0.001"}, {"wall.material", "\"glass\""}, {"wall.e_dry", "0.8"},
       {"gravity", "-9.8"}, {"effects", "[\"drag\", \"lubrication\", \"elastic\"]"}, {"drag.law", "\"schiller-naumann\""},
       {"lubrication.model", "\"asymptotic\""}, {"lubrication.cutoff", "2e-4"},
       {"added_mass.model", "\"seed\""}, {"added_mass.dw_floor", "0.01"}, {"contact.delta_ss", "0.02"},
       {"contact.delta_sl", "0.2"}, {"contact.e_dry", "0.9"}, {"contact.beta", "1.0"}, {"contact.law", "\"hertz\""},
       {"solver.integrator", "\"ida\""}, {"solver.linear_solver", "\"dense\""}, {"solver.krylov_tol", "0.1"},
       {"solver.rtol", "1e-7"}, {"solver.atol", "1e-9"}, {"solver.t_end", "0.9"}, {"solver.max_step", "1e-4"},
       {"solver.max_steps", "200000"}, {"solver.step_budget", "1e6"}, {"measure.window", "0.02"},
       {"measure.instant_gap", "0.05"}, {"measure.stall_fraction", "0.02"}, {"measure.bounces", "\"all\""},
       {"measure.fit_distance", "0.2"}, {"measure.at_gap", "0.2"}, {"measure.e", "\"fit_time\""},
       {"measure.ends_distance", "0.03"}, {"measure.ends_speed_change", "0.3"}, {"measure.ends_tolerance", "0.03"},
       {"measure.samples_per_window", "40"}, {"measure.disagreement", "0.1"}, {"measure.max_samples", "1e6"}, {"measure.energy_budget", "false"},
       {"output.dt", "1e-5"}});
}

TEST(SceneValues, EveryHistoryKeyChangesTheText) {
  const std::vector<Override> history = {{"effects", "[\"drag\", \"lubrication\", \"added_mass\", \"elastic\", \"history\"]"}};
  const std::string base = values_of("default", history);
  std::set<std::string> seen{base};
  for (const Override& o : std::vector<Override>{{"history.kernel", "\"kim\""}, {"history.evaluator", "\"soe\""},
                                                {"history.tolerance", "1e-5"}, {"history.modes", "20"}, {"history.min_lag", "1e-6"},
                                                {"history.horizon", "0.5"}, {"history.start", "\"impulsive\""},
                                                {"history.reynolds", "\"initial\""}, {"history.wall_correction", "\"added-mass\""},
                                                {"history.evaluator", "\"direct\""}}) {
    std::vector<Override> ov = history;
    ov.push_back(o);
    if (o.key == "history.reynolds") ov.push_back({"history.kernel", "\"mei-adrian\""});
    std::string changed;
    try {
      changed = values_of("default", ov);
    } catch (const std::exception& e) {
      ADD_FAILURE() << o.key << " refused: " << e.what();
      continue;
    }
    EXPECT_TRUE(seen.insert(changed).second) << o.key << "=" << o.value << " leaves the text unchanged or gives another key's";
  }
  std::vector<Override> step = history;
  step.push_back({"history.evaluator", "\"direct\""});
  const std::string direct = values_of("default", step);
  step.push_back({"history.direct_step", "1e-5"});
  EXPECT_NE(values_of("default", step), direct) << "history.direct_step";
}

TEST(SceneValues, EveryFlowKeyChangesTheText) {
  expect_every_key_counts(
      "coupled/gg3462",
      {{"flow.cells_per_diameter", "24"}, {"flow.levels", "3"}, {"flow.r_max", "1.5"}, {"flow.ahead", "1.0"},
       {"flow.behind", "1.5"}, {"flow.cfl", "0.4"}, {"flow.tau_p_fraction", "0.3"}, {"flow.theta", "0.6"},
       {"flow.krylov_tol", "1e-7"}, {"flow.krylov_max_iter", "400"}, {"flow.krylov_restart", "50"}, {"flow.ring_spacing", "1.5"},
       {"flow.preconditioner_bins", "2"}, {"flow.block_probe_stride", "8"}, {"flow.start", "\"impulsive\""}, {"flow.developed_distance", "2.0"},
       {"flow.developed_time", "0.01"}, {"flow.force_in_step", "\"held\""},
       {"flow.min_gap_cells", "2.0"}, {"flow.energy_margin", "0.5"}, {"flow.speed_jump", "4.0"}, {"flow.speed_jump_floor", "0.6"},
       {"flow.max_wall_hours", "2.0"}, {"flow.fields", "false"}, {"flow.fields_format", "\"csv\""}, {"flow.fields_every", "0.01"}});
}

TEST(SceneValues, EveryFluidKeyChangesTheText) {
  expect_every_key_counts("glass_steel_glycerol50", {{"fluid.mass_fraction", "0.6"}, {"fluid.temperature", "25.0"}});
}

TEST(SceneValues, KeysThatNeedAnotherKeyChangeTheText) {
  // Keys the scenes above cannot take alone: each with the key it needs.
  const std::vector<Override> asymptotic = {{"lubrication.model", "\"asymptotic\""}};
  EXPECT_NE(values_of("default", asymptotic), values_of("default", {asymptotic[0], {"lubrication.h_c", "0.5"}}));
  const std::vector<Override> no_added_mass = {{"effects", "[\"drag\", \"lubrication\", \"history\", \"elastic\", \"flow\"]"}};
  EXPECT_NE(values_of("coupled/gg3462", no_added_mass),
            values_of("coupled/gg3462", {no_added_mass[0], {"flow.added_mass_estimate", "false"}}));
  // flow.dt: a scene without flow.cfl (gg3462's [flow] gives it).
  const std::vector<Override> flow = {{"effects", "[\"drag\", \"lubrication\", \"added_mass\", \"elastic\", \"flow\"]"},
                                      {"solver.t_end", "0.01"}};
  EXPECT_NE(values_of("default", flow), values_of("default", {flow[0], flow[1], {"flow.dt", "1e-4"}}));
}
