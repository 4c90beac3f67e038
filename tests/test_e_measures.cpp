// SPDX-License-Identifier: BSD-3-Clause
// The measures of e (docs/bounces.md): contact_ends does not move with its window or with output.dt, a dry collision
// gives e_dry in every measure, the default is the experiments' procedure for the scene's kind, measure.e picks the
// measure, and a point that cannot be measured says why.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include "apps/sweep.hpp"
#include "model/collision_model.hpp"
#include "core/errors.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"
#include "run/bounces.hpp"
#include "run/first_contact.hpp"
#include "run/recorder.hpp"
#include "run/simulate.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;
namespace fs = std::filesystem;

namespace {

std::string scene_file(const std::string& name) { return data_dir() + "/scenes/" + name + ".toml"; }

/// e of contact_ends (the callers set measure.e to it).
double e_default(const Scene& sc) {
  const auto s = simulate(sc, false, Recording::kinematics).summary_json;
  EXPECT_EQ(s["e_is"], "contact_ends");
  return s["e"].is_number() ? s["e"].get<double>() : NAN;
}

/// Halving and doubling the contact_ends window and output.dt by 10 both ways move e by less than 0.01.
void expect_robust(const std::function<Scene(std::vector<Override>)>& load, const std::string& what) {
  SCOPED_TRACE(what);
  const std::vector<Override> base = {{"measure.e", "\"contact_ends\""}};
  const Scene sc = load(base);
  const double e0 = e_default(sc);
  ASSERT_TRUE(std::isfinite(e0));
  auto with = [&](const std::string& k, double v) {
    auto ov = base;
    ov.push_back({k, test::num(v)});
    return e_default(load(ov));
  };
  const double d = sc.measure.ends_distance, dt = sc.output.dt;
  for (auto [k, v] : std::vector<std::pair<std::string, double>>{
           {"measure.ends_distance", d / 2}, {"measure.ends_distance", 2 * d}, {"output.dt", dt / 10}, {"output.dt", 10 * dt}}) {
    const double e = with(k, v);
    EXPECT_LT(std::abs(e - e0), 0.01) << k << " = " << v << ": e = " << e << " against " << e0;
  }
  // output.dt alone: the same samples near contact, so e agrees to the integration's accuracy.
  EXPECT_NEAR(with("output.dt", 10 * dt), e0, 1e-5);
}

std::map<std::string, std::string> csv_row(const fs::path& csv, int point) {
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  for (int i = 0; i < point; ++i) std::getline(in, line);  // point 1: the first data row
  std::map<std::string, std::string> row;
  std::stringstream hs(header), ls(line);
  for (std::string h, v; std::getline(hs, h, ',');) {
    std::getline(ls, v, ',');
    row[h] = v;
  }
  return row;
}


/// Runs `imcol sweep` on the scene text (one job, no plot) into a fresh folder under the temporary directory; returns
/// the folder (its sweep output is in out/) and what the sweep printed.
std::pair<fs::path, std::string> run_sweep(const std::string& name, const std::string& scene, const std::string& vary, double from,
                                           double to, int points) {
  const fs::path dir = fs::temp_directory_path() / ("imcol_e_measures_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  { std::ofstream(dir / (name + ".toml")) << scene; }
  SweepOptions opt;
  opt.vary = vary;
  opt.from = from;
  opt.to = to;
  opt.points = points;
  opt.jobs = 1;
  opt.out = (dir / "out").string();
  opt.progress = false;
  opt.plot = false;
  ::testing::internal::CaptureStdout();
  const int status = sweep((dir / (name + ".toml")).string(), {}, opt);
  const std::string printed = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(status, 0) << printed;
  return {dir, printed};
}

}  // namespace

TEST(EMeasures, DefaultDoesNotMoveWithItsWindowOrOutputDtOnTheShippedBouncingScenes) {
  for (const char* name : {"default", "gg3462", "bouncing_steel", "seed_run1", "seed_run2", "seed_run3", "seed_run4", "seed_run5"})
    expect_robust([&](std::vector<Override> ov) { return load_scene(scene_file(name), ov); }, name);
}

TEST(EMeasures, DefaultDoesNotMoveWithItsWindowOrOutputDtFromSt10To1000) {
  // default.toml's viscosity swept over St ~ 10-1000 (reduced-order), eight points with a rebound.
  for (double mu : {0.2, 0.12, 0.07, 0.04, 0.02, 0.01, 0.006, 0.0033})
    expect_robust([&](std::vector<Override> ov) {
      ov.push_back({"fluid.viscosity", test::num(mu)});
      return load_scene(scene_file("default"), ov);
    }, "viscosity " + std::to_string(mu));
}

TEST(EMeasures, EveryNamedMeasureIsIndependentOfOutputDt) {
  // Every measure sample is kept, not only the rows: fit_time (the seed_run scenes' e), gondret_2002 and the others
  // agree at output.dt = 1e-2 (one row per 10 ms) with the default 1e-4 to the integration's accuracy.
  for (const char* name : {"bouncing_steel", "seed_run1", "default"}) {
    SCOPED_TRACE(name);
    const auto a = simulate(load_scene(scene_file(name)), false, Recording::kinematics).summary_json;
    const auto b = simulate(load_scene(scene_file(name), {{"output.dt", "1e-2"}}), false, Recording::kinematics).summary_json;
    ASSERT_EQ(a["bounces"].size(), b["bounces"].size());
    for (std::size_t k = 0; k < a["bounces"].size(); ++k)
      for (const auto& [m, v] : a["bounces"][k]["e_measures"].items()) {
        const auto& w = b["bounces"][k]["e_measures"][m]["e"];
        ASSERT_EQ(v["e"].is_number(), w.is_number()) << "contact " << k + 1 << " " << m;
        if (w.is_number()) {
          EXPECT_NEAR(w.get<double>(), v["e"].get<double>(), 1e-5) << "contact " << k + 1 << " " << m;
        }
      }
  }
}

TEST(EMeasures, TooManyMeasureSamplesAreRefusedNamingTheKey) {
  // default.toml (0.3 m/s, D = 12.7 mm, t_end 1 s): a window of 1e-5 D is 0.42 us, 32 samples each: 7.6e7 samples.
  auto refused = [](const std::vector<Override>& ov, const std::string& key) {
    try {
      simulate(load_scene(scene_file("default"), ov), false, Recording::kinematics);
      ADD_FAILURE() << key << ": not refused";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), key) << e.what();
      EXPECT_NE(std::string(e.what()).find("measure.max_samples"), std::string::npos) << e.what();
    }
  };
  refused({{"measure.ends_distance", "1e-5"}}, "measure.ends_distance");
  refused({{"measure.ends_distance", "1e-3"}, {"measure.samples_per_window", "10000"}}, "measure.samples_per_window");
  refused({{"measure.ends_distance", "1e-3"}, {"measure.max_samples", "1e5"}}, "measure.ends_distance");
  refused({{"measure.max_samples", "1e4"}}, "measure.max_samples");
  refused({{"solver.t_end", "1000"}}, "solver.t_end");  // 3.8e7 samples at the defaults
  // A 2 mm steel sphere released 2 m above a wall in a viscous liquid: a free fall would reach 5.8 m/s (9.4e7 samples
  // over 20 s); with drag its speed stays below the Stokes terminal speed, 0.15 m/s (2.4e6 samples).
  const std::string tall = "gravity = 9.81\n" + test::fluid(0.1, 1000) + test::sphere("steel", 0.002, -2.001, 0.0) +
                           test::wall("glass", 0.0) + "[drag]\nlaw = \"stokes\"\n[solver]\nt_end = 20.0\n[output]\ndt = 1e-2\n";
  const Scene with_drag = parse_scene(tall, "tall.toml");
  const model::CollisionModel model(with_drag);
  const double dt = run::measure_interval(model, with_drag);
  EXPECT_LT(with_drag.solver.t_end / dt, 1e7);
  EXPECT_GT(with_drag.solver.t_end / dt, 1e6);
  const Scene no_drag = parse_scene(tall, "tall.toml", {{"effects", "[\"lubrication\", \"added_mass\", \"elastic\", \"gravity\"]"}});
  const model::CollisionModel model2(no_drag);
  EXPECT_THROW(run::measure_interval(model2, no_drag), InputError);
}

TEST(EMeasures, AReboundTheFilmBrakesWithinTheWindowIsFittedOverAShorterWindowAndWarned) {
  // Started 1e-4 D from the wall at 0.01 m/s: the 0.02 D window is 25 ms, but the liquid film brakes the rebound to a
  // stop within 0.006 D. The window ends where U_rel has lost a quarter of its speed at the separation (0.57 ms).
  const Override ends{"measure.e", "\"contact_ends\""};
  const auto s = simulate(load_scene(data_dir() + "/scenes/hard/start_gap_1e-4D.toml", {ends}), false, Recording::kinematics).summary_json;
  double u_in = NAN, u_out = NAN;
  for (const auto& ev : s["events"]) {
    if (ev["event"] == "start inside the contact zone") u_in = ev["u_rel_m_s"].get<double>();
    if (ev["event"] == "gap=delta_ss (out)" && std::isnan(u_out)) u_out = ev["u_rel_m_s"].get<double>();
  }
  ASSERT_TRUE(std::isfinite(u_in) && std::isfinite(u_out));
  ASSERT_EQ(s["e_is"], "contact_ends");
  const double e = s["e"].get<double>(), e_sep = -u_out / u_in;
  EXPECT_NEAR(e, e_sep, 0.05) << "separation-speed ratio " << e_sep;
  const auto& ce = s["e_measures"]["contact_ends"];
  EXPECT_EQ(ce["shortened_by"], "rebound speed change");
  EXPECT_LT(ce["window_s"].get<double>(), 0.1 * ce["shortened_from_s"].get<double>());
  // The end slope misses U_rel at the separation by more than measure.ends_tolerance (0.02): the run says so.
  const double mis = ce["end_mismatch"]["rebound"].get<double>();
  EXPECT_NEAR(mis, std::abs(e - e_sep), 1e-9);
  EXPECT_GT(mis, 0.02);
  bool warned = false;
  for (const auto& w : s["warnings"]) warned = warned || w.get<std::string>().find("measure.ends_tolerance") != std::string::npos;
  EXPECT_TRUE(warned) << s["warnings"].dump();
  // Not with a tolerance above the mismatch; and e does not move with output.dt.
  const auto loose = simulate(load_scene(data_dir() + "/scenes/hard/start_gap_1e-4D.toml", {ends, {"measure.ends_tolerance", "0.05"}}),
                              false, Recording::kinematics).summary_json;
  for (const auto& w : loose["warnings"]) EXPECT_EQ(w.get<std::string>().find("measure.ends_tolerance"), std::string::npos) << w;
  const auto coarse = simulate(load_scene(data_dir() + "/scenes/hard/start_gap_1e-4D.toml", {ends, {"output.dt", "1e-2"}}),
                               false, Recording::kinematics).summary_json;
  EXPECT_NEAR(coarse["e"].get<double>(), e, 1e-5);
}

TEST(EMeasures, ContactEndsIsNotBiasedByGravity) {
  // A 6 mm steel sphere at terminal speed onto glass in silicone oil (St ~ 22): the 10 ms line (fit_time) averages
  // the deceleration of the rise; the parabolas at the contact's ends do not, and agree with e_instant.
  const std::string text = "gravity = 9.81\n" + test::fluid(0.1, 965) + test::sphere("steel", 0.006, -0.123, 0.0) +
                           test::wall("glass", 0.0) + "[drag]\nlaw = \"schiller-naumann\"\n[solver]\nmax_step = 4e-5\n";
  expect_robust([&](std::vector<Override> ov) { return parse_scene(text, "gravity.toml", ov); }, "gravity");
  const auto s = simulate(parse_scene(text, "gravity.toml", {{"measure.e", "\"contact_ends\""}})).summary_json;
  const double e = s["e"].get<double>();
  EXPECT_NEAR(e, s["e_instant"].get<double>(), 0.01);
  EXPECT_LT(s["e_measures"]["fit_time"]["e"].get<double>(), e - 0.2);
  // The rebound parabola takes up the deceleration: about g (1 − ρ_f/ρ_p) plus the drag, toward the wall (+z).
  const double a = s["e_measures"]["contact_ends"]["rebound"]["z1"]["a_m_s2"].get<double>();
  EXPECT_GT(a, 9.81 * (1 - 965.0 / 7780) * 0.5);
}

TEST(EMeasures, DryCollisionGivesTheDryRestitutionInEveryFitMeasure) {
  const std::string dry = test::sphere("steel", 0.0127, -0.0127, 0.2) + test::wall("zerodur", 0.0) + "[contact]\ne_dry = 0.9\n";
  const auto s = simulate(parse_scene(dry, "dry.toml")).summary_json;
  EXPECT_EQ(s["e_is"], "joseph_2001");  // the default for a sphere and a wall
  EXPECT_NEAR(s["e"].get<double>(), 0.9, 1e-6);
  for (const char* k : {"contact_ends", "yang_hunt_2006", "joseph_2001", "gondret_2002"})
    EXPECT_NEAR(s["e_measures"][k]["e"].get<double>(), 0.9, 1e-6) << k;
  EXPECT_TRUE(s["measures_disagree"].empty());
}

TEST(EMeasures, MeasureEPicksTheReportedMeasureAndDisagreementsAreNamed) {
  // A 2 mm glass bead on steel in 50 wt% glycerol-water at St ~ 18: the 10 ms line and the parabolas differ by ~0.25.
  const std::string bead = test::fluid(0.006, 1126) + test::sphere("glass", 0.002, -0.002, 0.2) + test::wall("steel", 0.0);
  const RunResult d_run = simulate(parse_scene(bead, "bead.toml", {{"measure.e", "\"contact_ends\""}}));
  const auto& d = d_run.summary_json;
  const auto f = simulate(parse_scene(bead, "bead.toml", {{"measure.e", "\"fit_time\""}})).summary_json;
  EXPECT_EQ(f["e_is"], "fit_time");
  EXPECT_DOUBLE_EQ(f["e"].get<double>(), f["e_measures"]["fit_time"]["e"].get<double>());
  EXPECT_DOUBLE_EQ(d["e"].get<double>(), d["e_measures"]["contact_ends"]["e"].get<double>());
  // Measures identical by construction (fit_time over 10 ms = yang_hunt_2006, peak_rebound = gondret_2002) are compared
  // once, under both names, and the warning is one line with the spread.
  ASSERT_TRUE(d["measures_disagree"].contains("fit_time/yang_hunt_2006")) << d["measures_disagree"].dump();
  EXPECT_FALSE(d["measures_disagree"].contains("fit_time"));
  EXPECT_FALSE(d["measures_disagree"].contains("yang_hunt_2006"));
  // The spread of the measures is information, not a warning: one plain line, e's measure first.
  for (const auto& w : d["warnings"]) EXPECT_EQ(w.get<std::string>().find("measure"), std::string::npos) << w;
  const std::string t = run::e_by_measure_line(parse_scene(bead, "bead.toml"), d_run.summary.bounces.at(0));
  EXPECT_EQ(t.find("contact_ends "), 0u) << t;
  EXPECT_NE(t.find("(e)"), std::string::npos) << t;
  EXPECT_NE(t.find("fit_time/yang_hunt_2006 "), std::string::npos) << t;
  EXPECT_EQ(t.find("yang_hunt_2006"), t.rfind("yang_hunt_2006")) << t;
  EXPECT_NE(t.find("spread "), std::string::npos) << t;
  EXPECT_EQ(t.find('\n'), std::string::npos) << t;
  // With another measure.window the two are different measures, compared under their own names.
  const Scene other = parse_scene(bead, "bead.toml", {{"measure.window", "0.012"}, {"measure.fit_distance", "0.2"}});
  EXPECT_EQ(run::measure_label(other, EMeasure::fit_time), "fit_time");
  EXPECT_EQ(run::measure_label(other, EMeasure::yang_hunt_2006), "yang_hunt_2006");
  EXPECT_EQ(run::measure_label(other, EMeasure::joseph_2001), "joseph_2001");
  EXPECT_EQ(run::measure_label(other, EMeasure::gondret_2002), "");
  EXPECT_EQ(run::measure_label(other, EMeasure::peak_rebound), "peak_rebound/gondret_2002");
  // The windows and the fitted parabolas are reported for the picture.
  const auto& ce = d["e_measures"]["contact_ends"];
  EXPECT_LT(ce["approach"]["t0_s"].get<double>(), ce["approach"]["t1_s"].get<double>());
  EXPECT_NEAR(ce["approach"]["t1_s"].get<double>(), d["contact"]["t_contact_s"].get<double>(), 1e-15);
  EXPECT_NEAR(ce["window_s"].get<double>(), 0.02 * 0.002 / d["bounces"][0]["impact_speed_at_delta_ss_m_s"].get<double>(), 1e-12);
  // A bad measure name is an input error naming the key.
  EXPECT_THROW(parse_scene(bead + "[measure]\ne = \"fit\"\n", "bad.toml"), InputError);
}

TEST(EMeasures, ARunThatEndedAtRestIsMeasuredAndASweepGivesNoUselessHint) {
  // The bead at 0.097 m/s (St ~ 8) stops on the wall at 16 ms: e = 0, and a longer t_end would change nothing.
  const std::string bead = test::fluid(0.006, 1126) + test::sphere("glass", 0.002, -0.002, 0.097) + test::wall("steel", 0.0);
  const auto s = simulate(parse_scene(bead, "bead.toml")).summary_json;
  ASSERT_TRUE(s["at_rest_since_s"].is_number());
  EXPECT_FALSE(s["t_end_too_short"].get<bool>());
  ASSERT_TRUE(s["e"].is_number());
  EXPECT_EQ(s["e"].get<double>(), 0.0);
  // In a sweep: measured, no t_end extension, no advice.
  const auto [dir, printed] = run_sweep("bead", bead, "velocity", 0.097, 0.3, 2);
  const auto row = csv_row(dir / "out" / "sweep.csv", 1);
  EXPECT_EQ(row.at("e"), "0");
  EXPECT_EQ(row.at("e_status"), "measured");
  EXPECT_EQ(row.at("message").find("t_end"), std::string::npos) << row.at("message");
  // The faster point rebounds; its message names the measures that disagree with e.
  const auto fast = csv_row(dir / "out" / "sweep.csv", 2);
  EXPECT_EQ(fast.at("e_status"), "measures_disagree");
  EXPECT_NE(fast.at("message").find("fit_time"), std::string::npos) << fast.at("message");
  EXPECT_NE(printed.find("named measures disagree with e (joseph_2001)"), std::string::npos) << printed;
  fs::remove_all(dir);
}

TEST(EMeasures, TEndTooShortIsJudgedByTheMeasureThatEIs) {
  // default.toml separates at 22.3 ms; t_end = 24.5 ms cuts the 10 ms lines (fit_time) but not the 0.88 ms parabolas.
  const std::vector<Override> ov = {{"solver.t_end", "0.0245"}};
  auto cut_warning = [](const nlohmann::ordered_json& s) {
    for (const auto& w : s["warnings"])
      if (w.get<std::string>().find("t_end cut") != std::string::npos) return true;
    return false;
  };
  const std::vector<Override> ov_ce = {{"solver.t_end", "0.0245"}, {"measure.e", "\"contact_ends\""}};
  const auto ce = simulate(load_scene(scene_file("default"), ov_ce), false, Recording::kinematics).summary_json;
  ASSERT_EQ(ce["e_is"], "contact_ends");
  ASSERT_TRUE(ce["e"].is_number());
  EXPECT_LT(ce["solver"]["t_final_s"].get<double>(), ce["bounces"][0]["t_separation_s"].get<double>() + 0.010);
  EXPECT_FALSE(ce["t_end_too_short"].get<bool>());
  EXPECT_FALSE(cut_warning(ce)) << ce["warnings"].dump();
  EXPECT_FALSE(ce["e_measures"]["contact_ends"]["cut_by_end_of_run"].get<bool>());
  auto ov_ft = ov;
  ov_ft.push_back({"measure.e", "\"fit_time\""});
  const auto ft = simulate(load_scene(scene_file("default"), ov_ft), false, Recording::kinematics).summary_json;
  ASSERT_EQ(ft["e_is"], "fit_time");
  EXPECT_TRUE(ft["t_end_too_short"].get<bool>());
  EXPECT_TRUE(cut_warning(ft)) << ft["warnings"].dump();
  // A window cut by t_end, not by the stop after the first rebound: the default t_end gives neither.
  EXPECT_FALSE(simulate(load_scene(scene_file("default"), {{"measure.e", "\"fit_time\""}}), false, Recording::kinematics)
                   .summary_json["t_end_too_short"].get<bool>());
}

TEST(EMeasures, APointThatNoTEndMeasuresSaysWhyWithoutAdvice) {
  // A start far from the wall with a tiny t_end: no collision by t_end. The sweep's retries (t_end x4) do not reach
  // contact either, so the message says why and that the longer t_end did not help.
  const std::string far = test::fluid(0.02, 1200) + test::sphere("steel", 0.0127, -0.5, 0.3) + test::wall("zerodur", 0.0) +
                          "[contact]\ne_dry = 0.97\n[solver]\nt_end = 0.05\n";
  const auto [dir, printed] = run_sweep("far", far, "viscosity", 0.02, 0.02, 1);
  const auto row = csv_row(dir / "out" / "sweep.csv", 1);
  EXPECT_TRUE(row.at("e").empty());
  EXPECT_EQ(row.at("e_status"), "not_measured");
  EXPECT_NE(row.at("message").find("no collision by t_end"), std::string::npos) << row.at("message");
  EXPECT_NE(row.at("message").find("still so with solver.t_end raised to 0.2 s"), std::string::npos) << row.at("message");
  EXPECT_EQ(row.at("message").find("(raise solver.t_end)"), std::string::npos) << row.at("message");
  EXPECT_NE(printed.find("e not measured at 1 of 1 points"), std::string::npos) << printed;
  fs::remove_all(dir);
}
