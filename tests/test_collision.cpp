// SPDX-License-Identifier: BSD-3-Clause
// Layers 2-4: exact dry solutions, conservation, integrator agreement, convergence, physical trends.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "run/simulate.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;

namespace {

std::string pair_scene(const std::string& fluid, double u1, double u2, const std::string& extra = "") {
  return fluid + test::sphere("steel", 0.0127, 0.0, u1) + test::sphere("glass", 0.010, 0.014, u2) + extra;
}

std::string wall_scene(const std::string& fluid, double u, const std::string& extra = "") {
  return fluid + test::sphere("steel", 0.0127, -0.0127, u) + test::wall("zerodur", 0.0) + "[contact]\ne_dry = 0.9\n" + extra;
}

RunResult collision_run(const std::string& toml, std::vector<Override> ov = {}) {
  return simulate(parse_scene(toml, "test.toml", ov));
}
double e_of(const RunResult& r) { return r.summary_json["e"].get<double>(); }

using test::fluid;

}  // namespace

class DryCollision : public ::testing::TestWithParam<std::string> {};

TEST_P(DryCollision, WallReturnsDryRestitution) {
  auto r = collision_run(wall_scene("", 0.2, "[solver]\nrtol = 1e-10\n"), {{"solver.integrator", "\"" + GetParam() + "\""}});
  EXPECT_NEAR(e_of(r), 0.9, 1e-6);
  EXPECT_NEAR(r.summary_json["e_instant"].get<double>(), 0.9, 1e-6);
  EXPECT_TRUE(r.summary_json["separated"].get<bool>());
  EXPECT_TRUE(r.summary_json["St"].is_null());
  // e_instant at a gap outside the contact zone (the rebound must run on until it is reached).
  auto far = collision_run(wall_scene("", 0.2, "[solver]\nrtol = 1e-10\n[measure]\ninstant_gap = 0.3\n"),
                 {{"solver.integrator", "\"" + GetParam() + "\""}});
  EXPECT_NEAR(far.summary_json["e_instant"].get<double>(), 0.9, 1e-6);
  EXPECT_NEAR(e_of(far), 0.9, 1e-6);
}

TEST_P(DryCollision, PairReturnsDryRestitutionAndConservesMomentum) {
  // Both spheres moving, unequal sizes and materials: e = min(e_steel, e_glass) = 0.97.
  auto r = collision_run(pair_scene("", 0.15, -0.05, "[solver]\nrtol = 1e-10\n"), {{"solver.integrator", "\"" + GetParam() + "\""}});
  EXPECT_NEAR(e_of(r), 0.97, 1e-6);
  // Momentum m1 u1 + m2 u2 at every sample equals the initial one.
  const double pi = 3.141592653589793;
  const double m1 = 7780 * pi / 6 * std::pow(0.0127, 3), m2 = 2540 * pi / 6 * std::pow(0.010, 3);
  const double p0 = m1 * 0.15 + m2 * -0.05;
  double worst = 0;
  for (const auto& row : r.rows) worst = std::max(worst, std::abs(m1 * row[2] + m2 * row[5] - p0) / std::abs(p0));
  EXPECT_LT(worst, 1e-9);
  // The contact force rose to the frozen Hertz peak W_o.
  EXPECT_NEAR(r.summary_json["max_contact_force_N"].get<double>() / r.summary_json["contact"]["W_o_N"].get<double>(), 1.0, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Integrators, DryCollision, ::testing::Values("cvode", "ida"));

TEST(ImmersedCollision, AddedMassForcesAreConservative) {
  // Ideal fluid limit (added mass only): ½ m_a(δ) U² is conserved outside the contact, so the
  // relative speed at any gap comes back multiplied by exactly e_d.
  for (double gap : {0.017, 0.05, 0.3}) {
    auto r = collision_run("effects = [\"added_mass\", \"elastic\"]\n" + wall_scene(fluid(0.01, 1200), 0.5),
                 {{"solver.rtol", "1e-10"}, {"measure.instant_gap", std::to_string(gap)}});
    EXPECT_NEAR(r.summary_json["e_instant"].get<double>(), 0.9, 1e-6) << "gap " << gap;
    EXPECT_LE(e_of(r), 0.9 + 1e-9);
  }
}

TEST(AddedMassModels, LagrangianEqualsSeedForEqualSpheres) {
  // (For a wall both names run the same code: A(δ) U_rel² reduces to the (6.8) terms.)
  const std::string equal = fluid(0.01) + test::sphere("glass", 0.0127, 0.0, 0.1) + test::sphere("glass", 0.0127, 0.016, 0.0);
  // Same relative motion: the pair's relative kinetic energy is ½ (m_p + ½ m_f (1 + 3W)) U_rel² / 2 in both.
  EXPECT_NEAR(e_of(collision_run(equal, {{"added_mass.model", "lagrangian"}, {"solver.rtol", "1e-10"}})),
              e_of(collision_run(equal, {{"added_mass.model", "seed"}, {"solver.rtol", "1e-10"}})), 1e-6);
}

TEST(AddedMassModels, LagrangianPairIsConservative) {
  // Ideal fluid, unequal pair: relative energy comes back times e_d at any gap; momentum
  // Σ (m_p + ½ m_f) U is conserved at every sample.
  const std::string scene = "effects = [\"added_mass\", \"elastic\"]\n" + pair_scene(fluid(0.01, 1200), 0.5, 0.0);
  for (double gap : {0.03, 0.1}) {
    auto r = collision_run(scene, {{"added_mass.model", "lagrangian"}, {"solver.rtol", "1e-10"}, {"measure.instant_gap", std::to_string(gap)}});
    EXPECT_NEAR(r.summary_json["e_instant"].get<double>(), 0.97, 1e-6) << gap;
    EXPECT_LE(e_of(r), 0.97 + 1e-9);
    const double pi = 3.141592653589793;
    const double v1 = pi / 6 * std::pow(0.0127, 3), v2 = pi / 6 * std::pow(0.010, 3);
    const double M1 = (7780 + 600) * v1, M2 = (2540 + 600) * v2;
    const double p0 = M1 * 0.5;
    double worst = 0;
    for (const auto& row : r.rows) worst = std::max(worst, std::abs(M1 * row[2] + M2 * row[5] - p0) / p0);
    EXPECT_LT(worst, 1e-9);
  }
}

TEST(AddedMassModels, SeedPerSphereFormIsNotConservativeForUnequalPairs) {
  // Characterises the seed's (6.8) applied per sphere: for unequal spheres it transfers energy into
  // the relative motion, so an ideal-fluid collision rebounds faster than a dry one (e > e_d).
  const std::string scene = "effects = [\"added_mass\", \"elastic\"]\n" + pair_scene(fluid(0.01, 1200), 0.5, 0.0, "[added_mass]\nmodel = \"seed\"\n");
  auto r = collision_run(scene, {{"solver.rtol", "1e-10"}, {"measure.instant_gap", "0.1"}});
  EXPECT_GT(r.summary_json["e_instant"].get<double>(), 0.97 + 1e-3);
}

TEST(ImmersedCollision, CvodeAndIdaAgree) {
  for (const std::string& scene : {wall_scene(fluid(0.02), 0.3), pair_scene(fluid(0.01), 0.2, 0.0),
                                   pair_scene(fluid(0.01), 0.2, 0.0, "[added_mass]\nmodel = \"lagrangian\"\n")}) {
    auto a = collision_run(scene, {{"solver.rtol", "1e-10"}});
    auto b = collision_run(scene, {{"solver.rtol", "1e-10"}, {"solver.integrator", "\"ida\""}});
    EXPECT_NEAR(e_of(a), e_of(b), 1e-6);
    EXPECT_NEAR(a.summary_json["min_gap_m"].get<double>(), b.summary_json["min_gap_m"].get<double>(), 1e-9);
    EXPECT_NEAR(a.summary_json["St"].get<double>() / b.summary_json["St"].get<double>(), 1.0, 1e-7);
  }
}

TEST(ImmersedCollision, RestitutionConvergesAsRtolTightens) {
  const std::string scene = wall_scene(fluid(0.02), 0.3);
  const double ref = e_of(collision_run(scene, {{"solver.rtol", "1e-12"}}));
  double prev = 1;
  for (const char* rt : {"1e-6", "1e-8", "1e-10"}) {
    const double err = std::abs(e_of(collision_run(scene, {{"solver.rtol", rt}})) - ref);
    EXPECT_LT(err, prev) << "rtol " << rt;
    prev = err;
  }
  EXPECT_LT(prev, 1e-7);
}

TEST(ImmersedCollision, RestitutionRisesWithStokesAndStaysBelowDry) {
  // Sweep the viscosity at fixed impact speed; every case reaches contact.
  double prev_e = -1, prev_st = 0;
  for (double mu : {0.5, 0.2, 0.08, 0.03, 0.01, 0.003}) {
    auto r = collision_run(wall_scene(fluid(mu, 1200), 0.3, "[solver]\nt_end = 0.3\n"));
    SCOPED_TRACE("mu " + std::to_string(mu));
    ASSERT_EQ(r.summary_json["contacts"].get<int>(), 1);
    const double e = e_of(r);
    const double st = r.summary_json["St"].get<double>();
    EXPECT_GE(e, 0.0);
    EXPECT_LE(e, 0.9);
    EXPECT_GE(e, prev_e) << "St " << st;
    EXPECT_GT(st, prev_st);
    if (st < 5) {  // stuck after contact: no rebound
      EXPECT_EQ(e, 0.0) << "St " << st;
      EXPECT_FALSE(r.summary_json["separated"].get<bool>());
    } else {
      EXPECT_TRUE(r.summary_json["separated"].get<bool>());
      EXPECT_GT(e, 0.0);
    }
    prev_e = e;
    prev_st = st;
  }
  EXPECT_GT(prev_e, 0.85);  // St ~ 1000: close to dry
}

TEST(ImmersedCollision, ApproachStoppedByTheFluidGivesZeroRestitution) {
  // Without the history force (with it the approach decays like t^-1/2 and reaches the wall).
  auto r = collision_run("effects = [\"drag\", \"lubrication\", \"added_mass\", \"elastic\"]\n" + wall_scene(fluid(2.0, 1200), 0.3, "[solver]\nt_end = 0.3\n"));
  EXPECT_EQ(r.summary_json["contacts"].get<int>(), 0);
  EXPECT_EQ(e_of(r), 0.0);
  EXPECT_GT(r.summary_json["min_gap_m"].get<double>(), 0.017 * 0.0127);
  // Without a stop the run reports no e at all.
  auto cut = collision_run(wall_scene(fluid(0.02), 0.3), {{"solver.t_end", "0.005"}});
  EXPECT_TRUE(cut.summary_json["e"].is_null());
  EXPECT_FALSE(cut.summary_json["warnings"].empty());
}

TEST(ImmersedCollision, SeedGroupMotionCaseBNeverTouches) {
  // Seed Fig. 6.9(b): the target is pushed through the liquid film, the spheres never touch, the gap
  // settles near 0.07 D and the pair moves on together.
  auto sc = load_scene(data_dir() + "/scenes/group_b.toml");
  auto r = simulate(sc);
  const auto& s = r.summary_json;
  EXPECT_EQ(s["contacts"].get<int>(), 0);
  const double gap_D = s["min_gap_m"].get<double>() / 0.0127;
  EXPECT_GT(gap_D, 0.05);
  EXPECT_LT(gap_D, 0.09);
  EXPECT_EQ(s["e"].get<double>(), 0.0);
  ASSERT_FALSE(s["group_velocity_m_s"].is_null());
  const auto& v = s["velocities_m_s"];
  const double ug = s["group_velocity_m_s"].get<double>();
  EXPECT_GT(ug, 0.0);
  EXPECT_LT(std::abs(v["U_r1"].get<double>() - v["U_r2"].get<double>()), 0.1 * ug);
}

TEST(ImmersedCollision, PairLubricationConservesMomentum) {
  // Lubrication and contact act equal and opposite: Σ m_p u is constant without drag and added mass.
  auto r = collision_run("effects = [\"lubrication\", \"elastic\"]\n" + pair_scene(fluid(0.05), 0.3, -0.1), {{"solver.rtol", "1e-10"}});
  const double pi = 3.141592653589793;
  const double m1 = 7780 * pi / 6 * std::pow(0.0127, 3), m2 = 2540 * pi / 6 * std::pow(0.010, 3);
  const double p0 = m1 * 0.3 - m2 * 0.1;
  double worst = 0;
  for (const auto& row : r.rows) worst = std::max(worst, std::abs(m1 * row[2] + m2 * row[5] - p0) / std::abs(p0));
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(e_of(r), 0.97);  // the film dissipates
  EXPECT_GT(e_of(r), 0.0);
}

TEST(ImmersedCollision, SeedLubricationActsInTheRatioOfTheRadii) {
  // lubrication.model = "seed": 6πμ a_m (λ(h/a*) − 1) U_rel on sphere m, so f_lub2 = −(a2/a1) f_lub1 (steel 12.7 mm,
  // glass 10 mm), and the summary says that the forces differ.
  auto r = collision_run("effects = [\"lubrication\", \"elastic\"]\n" + pair_scene(fluid(0.05), 0.3, -0.1, "[lubrication]\nmodel = \"seed\"\n"),
               {{"solver.rtol", "1e-10"}});
  const auto col = [&](const std::string& c) { return std::find(r.columns.begin(), r.columns.end(), c) - r.columns.begin(); };
  const auto i1 = col("f_lub1"), i2 = col("f_lub2"), iu = col("u_rel");
  ASSERT_LT(std::size_t(i2), r.columns.size());
  ASSERT_LT(std::size_t(iu), r.columns.size());
  int checked = 0, approaching = 0, separating = 0;
  for (const auto& row : r.rows)
    if (std::abs(row[i1]) > 1e-12) {
      EXPECT_NEAR(row[i2] / row[i1], -0.010 / 0.0127, 1e-12);
      ++checked;
      // The film resists the relative motion: it pushes the spheres apart while U_rel > 0 (sphere 1 back, sphere 2
      // on), and holds them together while they separate.
      if (row[iu] > 1e-6) {
        EXPECT_LT(row[i1], 0) << "t = " << row[0];
        EXPECT_GT(row[i2], 0) << "t = " << row[0];
        ++approaching;
      } else if (row[iu] < -1e-6) {
        EXPECT_GT(row[i1], 0) << "t = " << row[0];
        EXPECT_LT(row[i2], 0) << "t = " << row[0];
        ++separating;
      }
    }
  EXPECT_GT(checked, 10);
  EXPECT_GT(approaching, 5);
  EXPECT_GT(separating, 5);
  EXPECT_EQ(r.summary_json["model"]["lubrication.model"].get<std::string>(), "seed");
  EXPECT_NE(r.summary_json["model"]["lubrication.pair_forces"].get<std::string>().find("differ"), std::string::npos);
  EXPECT_GT(e_of(r), 0.0);
  EXPECT_LT(e_of(r), 0.97);
}

TEST(ImmersedCollision, SeedLubricationOnAWallIsBrenner) {
  // For a wall a* = a: the seed's law is Brenner's series, and the whole run is the same.
  const std::string scene = "effects = [\"drag\", \"lubrication\", \"added_mass\", \"elastic\"]\n" + wall_scene(fluid(0.05), 0.2);
  const auto b = collision_run(scene, {{"lubrication.model", "\"brenner\""}}), s = collision_run(scene, {{"lubrication.model", "\"seed\""}});
  EXPECT_EQ(e_of(s), e_of(b));
  EXPECT_EQ(s.summary_json["solver"]["steps"], b.summary_json["solver"]["steps"]);
  EXPECT_GT(e_of(b), 0.0);
  EXPECT_LT(e_of(b), 0.9);
}

TEST(ImmersedCollision, OnlyTheListedEffectsRun) {
  auto r = collision_run("effects = [\"drag\", \"elastic\"]\n" + wall_scene(fluid(0.02), 0.3));
  const auto& cols = r.columns;
  auto has = [&](const std::string& c) { return std::find(cols.begin(), cols.end(), c) != cols.end(); };
  EXPECT_TRUE(has("f_drag1"));
  EXPECT_FALSE(has("f_lub1"));
  EXPECT_FALSE(has("f_am1"));
  EXPECT_EQ(r.summary_json["effects"].size(), 2u);
  EXPECT_FALSE(r.summary_json["model"].contains("lubrication.model"));
  // Without lubrication and added mass, less is dissipated.
  EXPECT_GT(e_of(r), e_of(collision_run(wall_scene(fluid(0.02), 0.3))));
}

TEST(HardCases, ExtremeSpeedsAndViscositiesStayStable) {
  // From creeping (St ~ 0.03) to nearly dry (St ~ 1e6), both integrators: every run completes with a
  // collision (contact, or an approach stopped by the fluid), every sample is finite, e in [0, e_d],
  // and the fast, nearly inviscid impacts rebound.
  for (const char* integ : {"cvode", "ida"})
    for (double u : {0.01, 1.0, 5.0})
      for (double mu : {1e-5, 1.0}) {
        SCOPED_TRACE(std::string(integ) + " u=" + std::to_string(u) + " mu=" + std::to_string(mu));
        // The model without history (with it a creeping approach decays like t^-1/2 and does not stall by t_end).
        const std::vector<Override> ov = {{"solver.integrator", std::string("\"") + integ + "\""}, {"solver.t_end", "2.0"},
                                          {"output.dt", "1e-3"}, {"effects", "[\"drag\", \"lubrication\", \"added_mass\", \"elastic\"]"}};
        for (const std::string& scene :
             {wall_scene(fluid(mu, 1200), u), pair_scene(fluid(mu, 1200), u, 0.0, "[added_mass]\nmodel = \"lagrangian\"\n")}) {
          RunResult r;
          ASSERT_NO_THROW(r = collision_run(scene, ov));
          for (const auto& row : r.rows)
            for (double v : row) ASSERT_TRUE(std::isfinite(v));
          ASSERT_FALSE(r.summary_json["e"].is_null());
          const double e = e_of(r), ed = r.summary_json["contact"]["e_dry"].get<double>();
          EXPECT_GE(e, 0.0);
          EXPECT_LE(e, ed + 1e-6);
          if (r.summary_json["St_initial"].get<double>() > 1000) {
            EXPECT_TRUE(r.summary_json["separated"].get<bool>());
            EXPECT_GT(e, 0.9 * ed);
          }
        }
      }
}

TEST(Recording, KinematicsOnlyMeasuresTheSameCollision) {
  // Sweeps record positions and velocities only (the forces are evaluated where the model watches for rest):
  // the integration, the events and every measure of e are those of the full recording.
  for (const char* name : {"default.toml", "gg3462.toml", "bouncing_steel.toml"}) {
    SCOPED_TRACE(name);
    const Scene sc = load_scene(data_dir() + "/scenes/" + name);
    const RunResult full = simulate(sc), lean = simulate(sc, false, Recording::kinematics);
    for (const char* k : {"e", "e_instant", "e_measures", "events", "St", "min_gap_m", "at_rest_since_s", "contacts"})
      EXPECT_EQ(lean.summary_json[k], full.summary_json[k]) << k;
    // The bounces too, but for the energy budget, which a kinematic recording (e alone) leaves out.
    auto without_budget = [](nlohmann::ordered_json b) {
      for (auto& x : b) x.erase("energy_budget");
      return b;
    };
    EXPECT_EQ(without_budget(lean.summary_json["bounces"]), without_budget(full.summary_json["bounces"]));
    EXPECT_TRUE(lean.summary_json["energy_budget"].is_null());
    EXPECT_TRUE(full.summary_json["energy_budget"].is_object());
    EXPECT_EQ(lean.summary_json["solver"]["steps"], full.summary_json["solver"]["steps"]);
    EXPECT_TRUE(lean.summary_json["max_contact_force_N"].is_null());
    EXPECT_FALSE(full.summary_json["max_contact_force_N"].is_null());
    ASSERT_EQ(lean.rows.size(), full.rows.size());
    ASSERT_EQ(lean.columns.back(), "event");
    ASSERT_LT(lean.columns.size(), full.columns.size());
    for (std::size_t c = 0; c + 1 < lean.columns.size(); ++c) {
      ASSERT_EQ(lean.columns[c], full.columns[c]);
      for (std::size_t i = 0; i < lean.rows.size(); ++i) ASSERT_EQ(lean.rows[i][c], full.rows[i][c]) << lean.columns[c] << " row " << i;
    }
  }
}
