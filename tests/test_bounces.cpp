// SPDX-License-Identifier: BSD-3-Clause
// Every bounce (measure.bounces = "all") and the named measures of e (docs/bounces.md).
#include <gtest/gtest.h>

#include <string>

#include "run/simulate.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;

namespace {
std::string data_file(const std::string& name) { return data_dir() + "/scenes/" + name; }
}  // namespace

TEST(Bounces, ShippedSceneBouncesWithDecreasingApexesUntilAtRest) {
  const RunResult r = simulate(load_scene(data_file("bouncing_steel.toml")));
  const auto& s = r.summary_json;
  const auto& b = s["bounces"];
  ASSERT_GE(b.size(), 4u);
  const double e_dry = s["contact"]["e_dry"].get<double>();
  int rebounds = 0;
  double last_apex = 1e9, last_t = -1;
  for (const auto& x : b) {
    EXPECT_GT(x["t_contact_s"].get<double>(), last_t);
    last_t = x["t_contact_s"].get<double>();
    for (const char* k : {"e", "e_instant"}) {
      ASSERT_TRUE(x[k].is_number()) << k;
      EXPECT_GE(x[k].get<double>(), 0.0) << k;
      EXPECT_LE(x[k].get<double>(), e_dry) << k;
    }
    if (x["t_separation_s"].is_null()) {  // never separated: no flight, no apex
      EXPECT_TRUE(x["apex_gap_m"].is_null());
      EXPECT_TRUE(x["t_apex_s"].is_null());
      continue;
    }
    ++rebounds;
    const double apex = x["apex_gap_m"].get<double>();
    EXPECT_LT(apex, last_apex);
    last_apex = apex;
    EXPECT_GT(x["t_apex_s"].get<double>(), x["t_separation_s"].get<double>());
    EXPECT_GT(x["impact_velocity_m_s"].get<double>(), 0.0);
  }
  EXPECT_GE(rebounds, 3);
  // The run ends at rest (or at t_end): here the last contact never separates and the at-rest test ends it.
  const bool at_rest = s["at_rest_since_s"].is_number();
  EXPECT_TRUE(at_rest || s["solver"]["t_final_s"].get<double>() == r.scene.solver.t_end);
  EXPECT_TRUE(at_rest);
  EXPECT_LT(s["solver"]["t_final_s"].get<double>(), r.scene.solver.t_end);
  EXPECT_NEAR(s["e"].get<double>(), b[0]["e"].get<double>(), 1e-9);  // z fit and gap fit: the same line
}

TEST(Bounces, FirstModeStopsAfterTheFirstReboundWithTheSameFirstBounce) {
  const RunResult all = simulate(load_scene(data_file("bouncing_steel.toml")));
  const RunResult first = simulate(load_scene(data_file("bouncing_steel.toml"), {{"measure.bounces", "\"first\""}}));
  ASSERT_EQ(first.summary_json["bounces"].size(), 1u);
  EXPECT_NEAR(first.summary_json["e"].get<double>(), all.summary_json["e"].get<double>(), 1e-6);
  EXPECT_NEAR(first.summary_json["e_instant"].get<double>(), all.summary_json["e_instant"].get<double>(), 1e-9);
  // It stops one window after the separation, before the apex (40 ms later).
  EXPECT_LT(first.summary_json["solver"]["t_final_s"].get<double>(), all.summary_json["bounces"][0]["t_apex_s"].get<double>());
}

TEST(Bounces, EveryMeasureGivesTheDryRestitutionOfADryCollision) {
  // No fluid: constant velocities before and after the contact, so every measure is e_dry.
  const std::string dry = test::sphere("steel", 0.0127, -0.0127, 0.2) + test::wall("zerodur", 0.0) +
                          "[contact]\ne_dry = 0.9\n[solver]\nrtol = 1e-10\n[measure]\nat_gap = 0.2\nfit_distance = 0.3\n";
  const auto s = simulate(parse_scene(dry, "dry.toml")).summary_json;
  const auto& m = s["e_measures"];
  for (const char* k : {"fit_time", "fit_distance", "at_gap", "peak_rebound", "instant"})
    EXPECT_NEAR(m[k]["e"].get<double>(), 0.9, 1e-6) << k;
  EXPECT_NEAR(m["fit_distance"]["distance_m"].get<double>(), 0.3 * 0.0127, 1e-15);
  EXPECT_NEAR(m["at_gap"]["gap_m"].get<double>(), 0.2 * 0.0127, 1e-15);
}

TEST(Bounces, ANegativeFitIsClippedAndSaysWhy) {
  // A window longer than the rebound's rise: the fitted rebound moves toward the wall.
  const RunResult r = simulate(load_scene(data_file("bouncing_steel.toml"), {{"measure.window", "0.08"}, {"measure.e", "\"fit_time\""}}));
  const auto& s = r.summary_json;
  bool clipped = false;
  for (const auto& b : s["bounces"]) {
    const auto& ft = b["e_measures"]["fit_time"];
    if (!ft.contains("e_raw")) continue;
    clipped = true;
    EXPECT_LT(ft["e_raw"].get<double>(), 0.0);
    EXPECT_EQ(ft["e"].get<double>(), 0.0);
    EXPECT_TRUE(ft["note"].is_string());
  }
  ASSERT_TRUE(clipped);
  bool warned = false;
  for (const auto& w : s["warnings"]) warned = warned || w.get<std::string>().find("clipped to 0") != std::string::npos;
  EXPECT_TRUE(warned);  // e is the clipped measure: a warning; another measure's clipping is only its e_raw and note
}
