// SPDX-License-Identifier: BSD-3-Clause
// Gondret, Lance & Petit (2002)'s bouncing cases, shipped as data/scenes/gondret/st*.toml (reduced order, every bounce).
// Checked: each sphere reaches its terminal speed before the first impact (computed here independently from the
// Schiller–Naumann law), every case rebounds at least once and comes to rest, and the first bounce's e rises with St.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/materials.hpp"
#include "core/scene.hpp"
#include "run/simulate.hpp"

using namespace imcol;

namespace {

/// Terminal speed of a sphere under gravity with Schiller–Naumann drag: (ρ_p − ρ_f) g V = 6πμ a U (1 + 0.15 Re^0.687).
double terminal_speed(double rho_p, double rho_f, double mu, double d, double g) {
  const double pi = 3.141592653589793, a = 0.5 * d;
  const double weight = (rho_p - rho_f) * g * 4.0 / 3.0 * pi * a * a * a;
  auto excess = [&](double U) { return 6 * pi * mu * a * U * (1 + 0.15 * std::pow(rho_f * U * d / mu, 0.687)) - weight; };
  double lo = 0, hi = 100;
  for (int i = 0; i < 200; ++i) (excess(0.5 * (lo + hi)) > 0 ? hi : lo) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

}  // namespace

TEST(Gondret, ShippedCasesReachTerminalSpeedBounceAndComeToRestWithERisingWithSt) {
  double last_st = 0, last_e = -1;
  for (const std::string st : {"27", "100", "152", "192", "742"}) {
    SCOPED_TRACE("gondret/st" + st);
    const RunResult r = simulate(load_scene(data_dir() + "/scenes/gondret/st" + st + ".toml"));
    const auto& s = r.summary_json;
    const auto& sc = r.scene;
    const double U_t = terminal_speed(sc.spheres[0].density, sc.fluid->density, sc.fluid->viscosity, sc.spheres[0].diameter, sc.gravity);
    // Largest speed before the first contact: within 3 % of the terminal speed (the scenes release the sphere high enough).
    const double t_contact = s["bounces"][0]["t_contact_s"].get<double>();
    double u_max = 0;
    for (const auto& row : r.rows)
      if (row[0] < t_contact) u_max = std::max(u_max, row[2]);
    EXPECT_NEAR(u_max / U_t, 1.0, 0.03) << "U_t = " << U_t;
    ASSERT_TRUE(s["bounces"][0]["t_separation_s"].is_number());
    EXPECT_TRUE(s["at_rest_since_s"].is_number());
    const double St = s["St"].get<double>(), e = s["e"].get<double>();
    EXPECT_GT(St, last_st);
    EXPECT_GT(e, last_e);
    EXPECT_LT(e, s["contact"]["e_dry"].get<double>());
    last_st = St;
    last_e = e;
  }
}
