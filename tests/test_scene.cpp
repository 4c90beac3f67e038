// SPDX-License-Identifier: BSD-3-Clause
// Scene parsing and validation: every bad input names its key and place.
#include <gtest/gtest.h>

#include <string>

#include "core/errors.hpp"
#include "core/scene.hpp"
#include "tests/input_error.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;

namespace {
const std::string kWall = test::basic_wall_scene();

/// Parses `text` and expects an InputError whose message contains every fragment.
void expect_error(const std::string& text, std::initializer_list<const char*> fragments, const std::vector<Override>& ov = {}) {
  const std::string msg = test::input_error_of([&] { parse_scene(text, "bad.toml", ov); });
  ASSERT_FALSE(msg.empty()) << "no error for:\n" << text;
  for (const char* f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' missing in: " << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << "message must be one line: " << msg;
}
}  // namespace

TEST(Scene, ParsesWallSceneWithDefaults) {
  Scene sc = parse_scene(kWall, "wall.toml");
  EXPECT_EQ(sc.name, "wall");
  ASSERT_TRUE(sc.fluid);
  EXPECT_DOUBLE_EQ(sc.fluid->viscosity, 0.01);
  ASSERT_EQ(sc.spheres.size(), 1u);
  EXPECT_DOUBLE_EQ(sc.spheres[0].density, 7780);
  EXPECT_TRUE(sc.wall);
  EXPECT_DOUBLE_EQ(sc.contact.delta_ss, 0.017);  // wall default
  EXPECT_EQ(sc.lubrication.model, LubricationModel::brenner);
  EXPECT_TRUE(sc.has(Effect::drag) && sc.has(Effect::lubrication) && sc.has(Effect::added_mass) && sc.has(Effect::elastic));
  EXPECT_FALSE(sc.has(Effect::gravity));
  EXPECT_EQ(sc.solver.integrator, IntegratorMethod::cvode);
}

TEST(Scene, OverridesFromTheCommandLine) {
  Scene sc = parse_scene(kWall, "wall.toml",
                         {parse_override("solver.rtol=1e-9"), parse_override("sphere[0].velocity=0.5"),
                          parse_override("solver.integrator=ida"), parse_override("contact.delta_ss=0.02")});
  EXPECT_DOUBLE_EQ(sc.solver.rtol, 1e-9);
  EXPECT_DOUBLE_EQ(sc.spheres[0].velocity, 0.5);
  EXPECT_EQ(sc.solver.integrator, IntegratorMethod::ida);
  EXPECT_DOUBLE_EQ(sc.contact.delta_ss, 0.02);
  EXPECT_THROW(parse_override("novalue"), InputError);
  expect_error(kWall, {"--set", "sphere[3]"}, {parse_override("sphere[3].velocity=1")});
  expect_error(kWall, {"--set", "solver.bogus", "unknown key"}, {parse_override("solver.bogus=1")});
  // One --set sets one key: a value with a line break (which TOML would read as further keys) is refused.
  const std::string msg = test::input_error_of([] { parse_override("solver.rtol=1e-8\nsolver.bogus=1"); });
  EXPECT_FALSE(msg.empty()) << "a line break was accepted";
  EXPECT_NE(msg.find("key 'solver.rtol'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line break"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(Scene, NonzeroMagnitudesBelow1eMinus30AndImpossibleValuesAreRefused) {
  // Every number: 0 or of magnitude in [1e-30, 1e30] (tolerances, fractions and signed keys alike).
  for (const char* kv : {"solver.atol=1e-300", "solver.krylov_tol=1e-31", "measure.stall_fraction=1e-40", "sphere[0].velocity=1e-300",
                         "sphere[0].velocity=-1e-300", "gravity=1e-31", "measure.disagreement=1e-35"}) {
    const Override o = parse_override(kv);
    expect_error(kWall, {o.key.c_str(), "1e-30"}, {o});
  }
  EXPECT_NO_THROW(parse_scene(kWall, "wall.toml", {parse_override("solver.atol=1e-30")}));
  EXPECT_NO_THROW(parse_scene(kWall, "wall.toml", {parse_override("sphere[0].velocity=1e-30")}));
  // A viscosity beyond any liquid's (glass at its transition, 1e12 Pa s).
  expect_error(kWall, {"fluid.viscosity", "1e+12"}, {parse_override("fluid.viscosity=1e29")});
  EXPECT_NO_THROW(parse_scene(kWall, "wall.toml", {parse_override("fluid.viscosity=1e12")}));
}

TEST(Scene, InlineMaterialAndExplicitEffects) {
  std::string t = test::edit(kWall, "material = \"steel\"", "density = 2000.0\nyoungs_modulus = 1e9\npoisson_ratio = 0.3\ne_dry = 0.8");
  t = "effects = [\"drag\", \"elastic\"]\n" + t;
  Scene sc = parse_scene(t, "x.toml");
  EXPECT_DOUBLE_EQ(sc.spheres[0].density, 2000);
  EXPECT_TRUE(sc.has(Effect::drag));
  EXPECT_FALSE(sc.has(Effect::lubrication));
}

TEST(Scene, RejectsBadInput) {
  expect_error(test::edit(kWall, "viscosity = 0.01", "viscosity = -0.01"), {"bad.toml:3", "fluid.viscosity", "> 0"});
  expect_error(test::edit(kWall, "density = 1000.0", "density = -1.0"), {"bad.toml:2", "fluid.density"});
  expect_error(test::edit(kWall, "viscosity = 0.01", "viscosity = 0.01\ncolour = 3"), {"bad.toml:4", "fluid.colour", "unknown key"});
  expect_error(test::edit(kWall, "viscosity = 0.01", ""), {"fluid.viscosity", "missing"});
  expect_error(test::edit(kWall, "diameter = 0.0127\n", ""), {"sphere[0].diameter", "missing"});
  expect_error(test::edit(kWall, "\"steel\"", "\"unobtainium\""), {"sphere[0].material", "unknown material", "steel"});
  expect_error(test::edit(kWall, "position = -0.02", "position = -0.001"), {"wall.position", "overlap"});
  // Positions far from z = 0 would leave the gap without the digits of a contact.
  expect_error(test::edit(kWall, "position = -0.02", "position = -2e4"), {"bad.toml:", "sphere[0].position", "within 1e6"});
  expect_error(test::edit(kWall, "position = 0.0\n", "position = 1e29\n"), {"bad.toml:", "wall.position", "within 1e6"});
  expect_error(kWall + "[solver]\nrtol = 0.0\n", {"solver.rtol", "bad.toml:13"});
  expect_error(kWall + "[solver]\nrtol = -1e-6\n", {"solver.rtol"});
  expect_error(kWall + "[solver]\nrtol = 1e-20\n", {"solver.rtol"});
  expect_error(kWall + "[solver]\nintegrator = \"rk4\"\n", {"solver.integrator", "cvode | ida"});
  expect_error("effects = [\"magic\"]\n" + kWall, {"bad.toml:1", "effects", "unknown effect"});
  expect_error(kWall + "effects = [\"drag\"]\n", {"wall.effects", "unknown key"});
  expect_error(kWall + "[drag]\nlaw = \"newton\"\n", {"drag.law"});
  expect_error("[[sphere]\n", {"bad.toml:1", "TOML"});
  // The flow fields' files: a known format, and no format or interval when no fields are written.
  const std::string coupled = "effects = [\"drag\", \"elastic\", \"flow\"]\n" + kWall;
  expect_error(coupled + "[flow]\nfields_format = \"hdf5\"\n", {"flow.fields_format", "csv | vtk | both"});
  expect_error(coupled + "[flow]\nfields_every = -0.01\n", {"flow.fields_every"});
  expect_error(coupled + "[flow]\nfields = false\nfields_every = 0.01\n", {"flow.fields_every", "fields = true"});
  EXPECT_EQ(parse_scene(coupled + "[flow]\nfields_format = \"vtk\"\nfields_every = 0.01\n", "ok.toml").flow.fields_format,
            imcol::FieldsFormat::vtk);
}

TEST(Scene, RejectsOverlappingSpheresAndWrongLubrication) {
  const std::string pair = test::fluid(0.01) + test::sphere("glass", 0.0127, 0.0, 0.1) + test::sphere("glass", 0.0127, 0.02, 0.0);
  EXPECT_NO_THROW(parse_scene(pair, "pair.toml"));
  expect_error(test::edit(pair, "position = 0.02", "position = 0.01"), {"sphere[1].position", "overlap"});
  // Inside the contact zone: allowed while approaching (the contact starts at t = 0), an error otherwise.
  EXPECT_NO_THROW(parse_scene(test::edit(pair, "position = 0.02", "position = 0.0128"), "pair.toml"));
  expect_error(test::edit(test::edit(pair, "position = 0.02", "position = 0.0128"), "velocity = 0.1", "velocity = 0.0"),
               {"sphere[1].position", "contact zone", "not approaching"});
  expect_error(pair + "[lubrication]\nmodel = \"brenner\"\n", {"lubrication.model", "asymptotic"});
  expect_error(pair + "[lubrication]\nmodel = \"implicit\"\n", {"lubrication.model", "brenner | asymptotic | seed"});
  // h_c is the asymptotic law's range: with another law (given or the wall's default, brenner) it is an error.
  EXPECT_NO_THROW(parse_scene(pair + "[lubrication]\nh_c = 0.5\n", "pair.toml"));
  expect_error(pair + "[lubrication]\nmodel = \"seed\"\nh_c = 0.5\n", {"bad.toml:", "lubrication.h_c", "'asymptotic'", "'seed'"});
  const std::string wall = test::basic_wall_scene();
  expect_error(wall + "[lubrication]\nh_c = 0.5\n", {"lubrication.h_c", "'brenner'"});
  expect_error(pair + "[wall]\nmaterial = \"glass\"\nposition = 1.0\n", {"wall", "not both"});
}

TEST(Scene, DryScenesRejectFluidEffects) {
  const char* dry = R"(
effects = ["elastic", "drag"]
[[sphere]]
material = "steel"
diameter = 0.0127
position = 0.0
velocity = 0.1
[wall]
material = "steel"
position = 0.02
)";
  expect_error(dry, {"effects", "drag", "[fluid]"});
}

TEST(Scene, HistorySettingsAreReadAndChecked) {
  const std::string fx = "effects = [\"drag\", \"added_mass\", \"elastic\", \"history\"]\n" + kWall;
  const Scene sc = parse_scene(fx + "[history]\nkernel = \"kim\"\nevaluator = \"direct\"\nstart = \"impulsive\"\n", "h.toml");
  EXPECT_TRUE(sc.has(Effect::history));
  EXPECT_EQ(sc.history.kernel, KernelKind::kim);
  EXPECT_EQ(sc.history.evaluator, HistoryEvaluator::direct);
  EXPECT_EQ(sc.history.start, HistoryStart::impulsive);
  expect_error(fx + "[history]\nkernel = \"oseen\"\n", {"history.kernel", "unknown choice 'oseen'", "bad.toml:"});
  expect_error(fx + "[history]\nmodes = 1\n", {"history.modes", "[2, 400]"});
  expect_error(fx + "[history]\ntolerance = 0.0\n", {"history.tolerance"});
  expect_error(fx + "[history]\nmin_lag = 1e-3\nhorizon = 1e-3\n", {"history.horizon", "10 × min_lag"});
  expect_error(fx + "[history]\nmemory = 3\n", {"history.memory", "unknown key"});
  expect_error("effects = [\"drag\", \"elastic\"]\n" + kWall + "[history]\nkernel = \"basset\"\n", {"history.kernel", "needs the 'history' effect"});
  expect_error(kWall + "[solver]\nintegrator = \"ida\"\nlinear_solver = \"gmres\"\n", {"solver.linear_solver", "cvode integrator only"});
  // gmres and schur precondition the history modes: without them in the state the scene is refused, not the run.
  expect_error(kWall + "[solver]\nlinear_solver = \"schur\"\n", {"bad.toml:", "solver.linear_solver", "history.evaluator = \"soe\""});
  expect_error(kWall + "[history]\nevaluator = \"soe-step\"\n[solver]\nlinear_solver = \"gmres\"\n", {"solver.linear_solver", "memory modes"});
  EXPECT_NO_THROW(parse_scene(kWall + "[history]\nevaluator = \"soe\"\n[solver]\nlinear_solver = \"gmres\"\n", "ok.toml"));
}

// Found by tests/test_scene_fuzz.cpp: escaped newlines in string values and quoted keys used to
// break the one-line message; they are now written as escapes.
TEST(Scene, MessagesStayOnOneLineWithControlCharactersInTheInput) {
  expect_error(test::edit(kWall, "\"steel\"", "\"st\\neel\""), {"bad.toml:5", "sphere[0].material", "unknown material 'st\\neel'"});
  expect_error(test::edit(kWall, "viscosity = 0.01", "viscosity = 0.01\n\"a\\r\\nb\\u0001\" = 1"),
               {"bad.toml:4", "key 'fluid.a\\r\\nb\\x01'", "unknown key"});
}

// Found by tests/test_scene_fuzz.cpp: an integer beyond 2^53 was refused as "must be a number".
TEST(Scene, LargeIntegersAreNumbers) {
  const Scene sc = parse_scene("gravity = -9007199254740993\n" + kWall, "big.toml");
  EXPECT_EQ(sc.gravity, -9007199254740992.0);  // the nearest double
  const Scene fast = parse_scene(test::edit(kWall, "velocity = 0.2", "velocity = 9223372036854775807"), "big.toml");
  EXPECT_EQ(fast.spheres[0].velocity, 9223372036854775807.0);
}
