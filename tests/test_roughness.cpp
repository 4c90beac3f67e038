// SPDX-License-Identifier: BSD-3-Clause
// Roughness-limited lubrication (lubrication.limit = "roughness", docs/model-notes.md): the solids touch at the sum of
// the materials' roughness heights, the film's force acts down to there and not in contact, and the scene reader
// refuses what contradicts it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "core/scene.hpp"
#include "run/simulate.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;

namespace {
std::string rough_scene() { return data_dir() + "/scenes/steel_glass_rough.toml"; }
}  // namespace

TEST(Roughness, TheSolidsTouchAtTheSumOfTheMaterialsRoughnessHeights) {
  const Scene sc = load_scene(rough_scene());
  EXPECT_EQ(sc.lubrication.limit, LubricationLimit::roughness);
  EXPECT_NEAR(sc.lubrication.roughness, 2.4e-8 + 1.34e-7, 1e-15);  // steel + glass, data/materials.csv
  EXPECT_NEAR(sc.contact.delta_ss * 0.006, sc.lubrication.roughness, 1e-15);
  EXPECT_LT(sc.lubrication.cutoff, sc.contact.delta_ss);
  const Scene given = load_scene(rough_scene(), {{"lubrication.roughness", "1e-6"}});
  EXPECT_NEAR(given.contact.delta_ss * 0.006, 1e-6, 1e-15);
}

TEST(Roughness, TheFilmActsDownToTheRoughnessHeightAndNotInContact) {
  const RunResult r = simulate(load_scene(rough_scene()));
  const auto& s = r.summary_json;
  ASSERT_TRUE(s["e"].is_number());
  double lub_in_contact = NAN, lub_rebound = NAN;
  for (const auto& p : s["energy_budget"]["phases"]) {
    if (p["phase"] == "contact") lub_in_contact = p["work_J"]["lubrication"].get<double>();
    if (p["phase"] == "rebound") lub_rebound = p["dissipated_per_impact_energy"]["lubrication"].get<double>();
  }
  EXPECT_EQ(lub_in_contact, 0.0);  // no film force between the inward and outward crossings of the roughness height
  EXPECT_GT(lub_rebound, 0.05);    // the film brakes the rebound from the roughness height on
  // Nothing else dissipates in the contact but the solids (and the history force's memory, a little).
  EXPECT_LT(std::abs(s["energy_budget"]["phases"][1]["dissipated_per_impact_energy"]["drag"].get<double>()), 1e-3);
  // At e_instant (at the roughness height) the rebound leaves at nearly e_dry; the camera sees the film's loss.
  EXPECT_GT(s["e_instant"].get<double>(), 0.9);
  EXPECT_LT(s["e"].get<double>(), 0.5);
}

TEST(Roughness, ContradictoryKeysAreRefusedByName) {
  auto refused_at = [](const std::vector<Override>& ov) {
    try {
      load_scene(data_dir() + "/scenes/steel_glass_rough.toml", ov);
    } catch (const InputError& e) {
      return e.key();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused_at({{"contact.law", "\"ramp\""}}), "lubrication.limit");
  EXPECT_EQ(refused_at({{"contact.delta_ss", "0.01"}}), "contact.delta_ss");
  EXPECT_EQ(refused_at({{"lubrication.roughness", "-1e-7"}}), "lubrication.roughness");
  EXPECT_EQ(refused_at({{"lubrication.limit", "\"cutoff\""}, {"lubrication.roughness", "1e-7"}}), "lubrication.roughness");
  // No roughness known for either surface (zerodur has none, an inline sphere neither).
  const std::string bare = test::fluid(0.1, 965) + test::sphere("nylon", 0.006, -0.009, 0.5) + test::wall("zerodur", 0.0) +
                           "[lubrication]\nlimit = \"roughness\"\n[contact]\nlaw = \"hertz\"\n";
  EXPECT_THROW(parse_scene(bare, "bare.toml"), InputError);
}
