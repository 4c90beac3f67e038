// SPDX-License-Identifier: BSD-3-Clause
// Close names (core/close_names.hpp) and the "did you mean" of the scene reader: an unknown key is reported at its
// file and line (or as an override) with the close known keys, before the key it was meant to be is missed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/close_names.hpp"
#include "core/scene.hpp"
#include "core/scene_keys.hpp"
#include "tests/imcol_process.hpp"
#include "tests/input_error.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;

namespace {

/// The message parsing `text` (with overrides `ov`) throws, as file `bad.toml`.
std::string close_names_error_of(const std::string& text, const std::vector<std::string>& ov = {}) {
  std::vector<Override> overrides;
  for (const auto& o : ov) overrides.push_back(parse_override(o));
  return test::input_error_of([&] { parse_scene(text, "bad.toml", overrides); });
}

const std::string kCloseNamesPair = test::fluid(0.01) + test::sphere("steel", 0.01, -0.02, 0.2) + test::sphere("steel", 0.01, 0.0, 0.0);

}  // namespace

TEST(CloseNames, EditDistanceCountsSwapsOfNeighboursAsOneEdit) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("viscocity", "viscosity"), 1u);
  EXPECT_EQ(edit_distance("densiyt", "density"), 1u);  // a swap
  EXPECT_EQ(edit_distance("ab", "ba"), 1u);
  EXPECT_EQ(edit_distance("ca", "abc"), 3u);  // optimal string alignment: no edit of a swapped pair
  EXPECT_EQ(edit_distance("velocity", "velocity"), 0u);
}

TEST(CloseNames, OnlyCloseNamesAreSuggestedClosestFirst) {
  EXPECT_EQ(allowed_edits(3), 1u);
  EXPECT_EQ(allowed_edits(8), 2u);
  EXPECT_EQ(allowed_edits(12), 4u);
  const std::vector<std::string> keys = scene_keys::fluid;
  EXPECT_EQ(close_names("viscocity", keys), std::vector<std::string>{"viscosity"});
  EXPECT_EQ(close_names("densty", keys), std::vector<std::string>{"density"});
  EXPECT_TRUE(close_names("colour", keys).empty());
  EXPECT_TRUE(close_names("density", keys).empty());  // the name itself is no suggestion
  EXPECT_EQ(close_names("rtol", scene_keys::solver), (std::vector<std::string>{"atol"}));
  EXPECT_EQ(did_you_mean("viscocity", keys), "; did you mean 'viscosity'?");
  EXPECT_EQ(did_you_mean("ato", {"atol", "rtol", "t_end"}), "; did you mean 'atol'?");
  EXPECT_EQ(did_you_mean("xtol", {"atol", "rtol"}), "; did you mean 'atol' or 'rtol'?");
  EXPECT_EQ(did_you_mean("colour", keys), "");
}

TEST(CloseNames, AMisspeltKeyIsReportedAtItsLineBeforeTheKeyItMeantIsMissed) {
  // viscosity is required without `fluid`: the misspelling is named, not "fluid.viscosity: missing".
  const std::string msg = close_names_error_of(test::edit(test::basic_wall_scene(), "viscosity = ", "viscocity = "));
  EXPECT_EQ(msg, "bad.toml:3: key 'fluid.viscocity': unknown key; did you mean 'viscosity'?");
  const std::string sphere = close_names_error_of(test::edit(test::basic_wall_scene(), "diameter = ", "diamter = "));
  EXPECT_EQ(sphere, "bad.toml:6: key 'sphere[0].diamter': unknown key; did you mean 'diameter'?");
  const std::string table = close_names_error_of(test::edit(test::basic_wall_scene(), "[fluid]", "[fluids]"));
  EXPECT_EQ(table, "bad.toml:1: key 'fluids': unknown key; did you mean 'fluid'?");
  // No close key: the message is as before.
  EXPECT_EQ(close_names_error_of(test::basic_wall_scene() + "[solver]\ncolour = 3\n"), "bad.toml:13: key 'solver.colour': unknown key");
}

TEST(CloseNames, OverridesGetTheSameSuggestionsAndArraysTheirIndex) {
  const std::string set = close_names_error_of(test::basic_wall_scene(), {"fluid.viscocity=0.02"});
  EXPECT_EQ(set, "command line (--set/--rtol/--atol/--integrator): key 'fluid.viscocity': unknown key; did you mean 'viscosity'?");
  EXPECT_EQ(close_names_error_of(test::basic_wall_scene(), {"sphere.velocity=0.3"}),
            "--set: key 'sphere.velocity': a scene's spheres are sphere[0]: use 'sphere[0].velocity'");
  EXPECT_EQ(close_names_error_of(kCloseNamesPair, {"sphere.velocity=0.3"}),
            "--set: key 'sphere.velocity': a scene's spheres are sphere[0] and sphere[1]: use 'sphere[0].velocity'");
  EXPECT_EQ(close_names_error_of(kCloseNamesPair, {"sphere.material.x=1"}),
            "--set: key 'sphere.material.x': a scene's spheres are sphere[0] and sphere[1]: use 'sphere[0].material.x'");
  // An unknown choice names the close spelling too.
  const std::string choice = close_names_error_of(test::basic_wall_scene(), {"solver.integrator=cvod"});
  EXPECT_NE(choice.find("unknown choice 'cvod' (expected "), std::string::npos) << choice;
  EXPECT_NE(choice.find("; did you mean 'cvode'?"), std::string::npos) << choice;
  // So do an unknown effect, material and fluid.
  const std::string effect = close_names_error_of(test::basic_wall_scene(), {"effects=[\"dragg\", \"elastic\"]"});
  EXPECT_NE(effect.find("unknown effect 'dragg' (expected "), std::string::npos) << effect;
  EXPECT_NE(effect.find("); did you mean 'drag'?"), std::string::npos) << effect;
  const std::string material = close_names_error_of(test::basic_wall_scene(), {"sphere[0].material=steal"});
  EXPECT_NE(material.find("unknown material 'steal' (known: "), std::string::npos) << material;
  EXPECT_NE(material.find("); did you mean 'steel'?"), std::string::npos) << material;
  const std::string fluid = close_names_error_of(test::basic_wall_scene(), {"fluid.fluid=watr"});
  EXPECT_NE(fluid.find("); did you mean 'water'?"), std::string::npos) << fluid;
}

TEST(CloseNames, TheCommandLineReportsTheMisspeltLineAndKeepsItsOwnWords) {
  const auto dir = std::filesystem::temp_directory_path() / "imcol_close_names";
  std::filesystem::create_directories(dir);
  const auto scene = dir / "misspelt.toml";
  std::ofstream(scene) << test::edit(test::basic_wall_scene(), "viscosity = ", "viscocity = ");
  const auto file = test::run_imcol("run " + scene.string() + " --quiet --no-plot --out " + (dir / "out").string(), dir / "run");
  EXPECT_EQ(file.status, 2) << file.err;
  EXPECT_EQ(file.err, "imcol: error: " + scene.string() + ":3: key 'fluid.viscocity': unknown key; did you mean 'viscosity'?\n");
  const auto set = test::run_imcol("run default --quiet --no-plot --set sphere.velocity=0.3 --out " + (dir / "out").string(), dir / "set");
  EXPECT_EQ(set.status, 2) << set.err;
  EXPECT_EQ(set.err, "imcol: error: --set: key 'sphere.velocity': a scene's spheres are sphere[0]: use 'sphere[0].velocity'\n");
  std::filesystem::remove_all(dir);
}
