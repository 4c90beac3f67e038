// SPDX-License-Identifier: BSD-3-Clause
// The contact laws (contact/contact_law.hpp): the seed's ramp and Hertz with Tsuji's nonlinear damping.
// Dry restitution, Hertz's contact time and energy balance, a force that never pulls, a start inside the contact zone,
// and both laws on an immersed scene.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "contact/formulas.hpp"
#include "contact/hertz_law.hpp"
#include "contact/table_data.hpp"
#include "contact/ramp_law.hpp"
#include "core/errors.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"
#include "run/simulate.hpp"
#include "tests/scene_text.hpp"

using namespace imcol;

namespace {

RunResult run_toml(const std::string& toml, std::vector<Override> ov = {}) { return simulate(parse_scene(toml, "test.toml", ov)); }

std::string law_line(const std::string& law) { return "law = \"" + law + "\"\n"; }

// A dry steel sphere onto a zerodur wall at 0.2 m/s.
std::string dry_wall(const std::string& law, double e_dry) {
  return test::sphere("steel", 0.0127, -0.0127, 0.2) + test::wall("zerodur", 0.0) + "[contact]\ne_dry = " + test::num(e_dry) +
         "\n" + law_line(law) + "[solver]\nrtol = 1e-10\n";
}

// A dry steel pair, sphere 2 at rest.
std::string dry_pair(const std::string& law, double e_dry, double u) {
  return test::sphere("steel", 0.0127, 0.0, u) + test::sphere("steel", 0.0127, 0.0152, 0.0) + "[contact]\ne_dry = " +
         test::num(e_dry) + "\n" + law_line(law) + "[solver]\nrtol = 1e-10\nt_end = 0.2\n";
}

// The gap at the U_rel = 0 event (peak compression), m.
double gap_at_unload(const RunResult& r) {
  for (const auto& ev : r.summary_json["events"])
    if (ev["event"].get<std::string>().rfind("u_rel=0 (loading", 0) == 0) return ev["gap_m"].get<double>();
  ADD_FAILURE() << "no unload event";
  return NAN;
}

const double kPi = 3.141592653589793;
double steel_mass(double d) { return 7780 * kPi / 6 * d * d * d; }

}  // namespace

TEST(TsujiDamping, AlphaReturnsTheAskedRestitution) {
  // The dimensionless problem: undamped, Hertz's contact time 2.943 ξ_max/U with ξ_max = (5/4)^{2/5} L.
  const auto free = contact::tsuji_impact(0.0);
  EXPECT_NEAR(free.e, 1.0, 1e-9);
  EXPECT_NEAR(free.x_max, std::pow(1.25, 0.4), 1e-8);
  EXPECT_NEAR(free.t_contact / (2.943 * free.x_max), 1.0, 1e-3);
  for (double e : {0.97, 0.9, 0.5, 0.1, 0.01}) {
    const double a = contact::tsuji_alpha(e);
    EXPECT_NEAR(contact::tsuji_impact(a).e, e, 1e-10) << "e = " << e;
  }
  EXPECT_EQ(contact::tsuji_alpha(1.0), 0.0);
  EXPECT_THROW(contact::tsuji_alpha(0.5 * contact::tsuji_min_e()), std::domain_error);
}

TEST(ContactLaws, HertzForceNeverPulls) {
  contact::ContactPair p{0.004, 1e11, 0.003, 0.5, 1e-4, 0.0127, 0.008, 0, "test.toml"};
  const contact::HertzLaw law(p);
  ASSERT_GT(law.eta(), 0);
  int clipped = 0;
  for (int i = -20; i <= 120; ++i) {
    const double gap = p.delta_ss_m * (1 - i / 100.0);  // from above δ_SS to 20 % past it
    for (double u : {-10.0, -1.0, -0.1, -1e-3, 0.0, 1e-3, 0.1, 1.0, 10.0}) {
      const double f = law.force(gap, u);
      EXPECT_GE(f, 0.0) << "gap " << gap << " u_rel " << u;
      if (i > 0 && f == 0) ++clipped;
      if (i <= 0) {
        EXPECT_EQ(f, 0.0);
      }
      // Where it is not clipped it is Hertz plus the damping.
      const double xi = p.delta_ss_m - gap;
      if (f > 0) {
        EXPECT_NEAR(f, law.stiffness() * std::pow(xi, 1.5) + law.eta() * std::pow(xi, 0.25) * u, 1e-9 * f);
      }
    }
  }
  EXPECT_GT(clipped, 0);  // the clip acts (fast separation at a small overlap)
}

TEST(ContactLaws, DryCollisionReturnsDryRestitution) {
  for (const char* law : {"ramp", "hertz"}) {
    for (double e_dry : {0.97, 0.9, 0.5}) {
      const auto w = run_toml(dry_wall(law, e_dry));
      const auto p = run_toml(dry_pair(law, e_dry, 0.1));
      std::printf("dry %s e_dry = %.2f: e(wall) - e_dry = %.2e, e(pair) - e_dry = %.2e\n", law, e_dry,
                  w.summary_json["e"].get<double>() - e_dry, p.summary_json["e"].get<double>() - e_dry);
      EXPECT_NEAR(w.summary_json["e"].get<double>(), e_dry, 1e-6) << law;
      EXPECT_NEAR(p.summary_json["e"].get<double>(), e_dry, 1e-6) << law;
      EXPECT_EQ(w.summary_json["contact"]["law"].get<std::string>(), law);
      EXPECT_EQ(w.summary_json["model"]["contact.law"].get<std::string>(), law);
    }
  }
}

TEST(ContactLaws, HertzContactTimeAndEnergyBalance) {
  // Undamped (e_dry = 1), a dry steel pair: the contact lasts Hertz's t_c = 2.943 ξ_max/U and the elastic work up to the
  // peak compression, (2/5) k ξ_max^{5/2}, equals the relative kinetic energy ½ m* U² at impact.
  for (double u : {0.05, 0.3, 1.0}) {
    const auto r = run_toml(dry_pair("hertz", 1.0, u));
    const auto& c = r.summary_json["contact"];
    const double U = c["impact_speed_m_s"].get<double>();
    const double m_star = 0.5 * steel_mass(0.0127), a_star = 0.5 * 0.0127 / 2;
    const Material& steel = *MaterialTable::builtin().find("steel");
    const double E = steel.youngs_modulus, nu = steel.poisson_ratio;
    const double E_star = contact::effective_modulus(E, nu, E, nu);
    const double t_c = c["t_separation_s"].get<double>() - c["t_contact_s"].get<double>();
    const double t_hertz = contact::hertz_contact_time(m_star, U, E_star, a_star);
    const double xi_max = c["delta_ss_m"].get<double>() - gap_at_unload(r);
    const double work = 0.4 * (4.0 / 3.0) * E_star * std::sqrt(a_star) * std::pow(xi_max, 2.5);
    const double kinetic = 0.5 * m_star * U * U;
    std::printf("hertz U = %.2f: t_c/t_Hertz - 1 = %.2e, work/kinetic - 1 = %.2e, e - 1 = %.2e\n", u, t_c / t_hertz - 1,
                work / kinetic - 1, r.summary_json["e"].get<double>() - 1);
    EXPECT_NEAR(t_c / t_hertz, 1.0, 0.01);
    EXPECT_NEAR(work / kinetic, 1.0, 1e-6);
    EXPECT_NEAR(r.summary_json["e"].get<double>(), 1.0, 1e-6);  // no kinetic energy lost over the contact
    EXPECT_NEAR(c["xi_max_m"].get<double>() / xi_max, 1.0, 1e-6);
  }
}

TEST(ContactLaws, StartInsideTheZoneAtOneMetrePerSecond) {
  // A steel pair 10 µm apart closing at 1 m/s: the Hertz indentation (~30 µm) exceeds what the ramp can store over
  // the shortened zone (refused), while the Hertz law runs.
  const std::string scene = test::fluid(0.01) + test::sphere("steel", 0.0127, 0.0, 1.0) +
                            test::sphere("steel", 0.0127, 0.0127 + 1e-5, 0.0) + "[solver]\nt_end = 0.02\n";
  try {
    run_toml(scene);
    ADD_FAILURE() << "the ramp took a start it cannot store";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sphere[0].position"), std::string::npos) << e.what();
  }
  const auto r = run_toml(scene, {{"contact.law", "\"hertz\""}});
  EXPECT_EQ(r.summary_json["contact"]["law"].get<std::string>(), "hertz");
  EXPECT_EQ(r.summary_json["contact"]["t_contact_s"].get<double>(), 0.0);
  EXPECT_TRUE(r.summary_json["separated"].get<bool>());
  const double e = r.summary_json["e"].get<double>();
  std::printf("start inside at 1 m/s, hertz: e = %.6f\n", e);
  EXPECT_GT(e, 0.0);
  EXPECT_LE(e, 0.97);
}

TEST(ContactLaws, ImmersedDefaultSceneWithBothLaws) {
  const std::string path = data_dir() + "/scenes/default.toml";
  const auto ramp = simulate(load_scene(path, {}));
  const auto hertz = simulate(load_scene(path, {{"contact.law", "\"hertz\""}}));
  const double e_dry = ramp.summary_json["contact"]["e_dry"].get<double>();
  const double er = ramp.summary_json["e"].get<double>(), eh = hertz.summary_json["e"].get<double>();
  std::printf("default.toml: e(ramp) = %.6f, e(hertz) = %.6f, e_dry = %.2f\n", er, eh, e_dry);
  for (double e : {er, eh}) {
    EXPECT_GE(e, 0.0);
    EXPECT_LE(e, e_dry);
  }
  EXPECT_EQ(hertz.summary_json["contact"]["law"].get<std::string>(), "hertz");
}

// α(e) from the shipped nodes of e(α): the nodes are the impacts themselves, and across e_dry's range the α found
// gives back the asked e within 1e-10 (the impact's own accuracy is 1e-9).
TEST(ContactLaws, TsujiAlphaFromTheShippedNodes) {
  using contact::table_data::tsuji_n, contact::table_data::tsuji_e_nodes, contact::table_data::tsuji_alpha_max;
  for (int i : {0, 1, 7, 250, 999, tsuji_n - 1})
    EXPECT_EQ(tsuji_e_nodes[i], contact::tsuji_impact(tsuji_alpha_max * i / (tsuji_n - 1)).e) << "node " << i;
  EXPECT_EQ(contact::tsuji_min_e(), tsuji_e_nodes[tsuji_n - 1]);
  const double lo = std::log(contact::tsuji_min_e()), hi = std::log(0.9999);
  for (int k = 0; k <= 40; ++k) {
    const double e = std::exp(lo + (hi - lo) * (k + 0.5) / 41);
    EXPECT_NEAR(contact::tsuji_impact(contact::tsuji_alpha(e)).e, e, 1e-10) << "e = " << e;
  }
}
