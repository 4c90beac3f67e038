// SPDX-License-Identifier: BSD-3-Clause
// The impact speed's bound (model/impact_speed.hpp) and the history memory it sets for a sphere released from rest:
// the shortest lag the exponentials resolve is below the impact's time scales, and e has converged in it.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "contact/formulas.hpp"
#include "core/data_dir.hpp"
#include "core/scene.hpp"
#include "model/collision_model.hpp"
#include "model/impact_speed.hpp"
#include "run/simulate.hpp"

namespace {

using namespace imcol;

const std::string kReleasedScene = "/scenes/hard/released_under_gravity.toml";

double choice_of(const model::CollisionModel& m, const std::string& key) {
  for (const auto& [k, v] : m.choices())
    if (k == key) return std::stod(v);
  return NAN;
}

double released_e(std::vector<Override> ov) {
  ov.push_back({"solver.rtol", "1e-10"});
  return simulate(load_scene(data_dir() + kReleasedScene, ov), false, Recording::kinematics).summary.e.value();
}

}  // namespace

TEST(ImpactSpeed, BoundsByTheInitialSpeedTheFallAndTheTerminalSpeed) {
  // No gravity: the initial approach speed.
  const Scene still = load_scene(data_dir() + "/scenes/default.toml");
  EXPECT_DOUBLE_EQ(model::impact_speed_bound(still, model::PairGeometry(still)), 0.3);
  // Released from rest without drag: the fall over the initial gap at the buoyant acceleration, √(2 g' h0).
  const Scene fall = load_scene(data_dir() + kReleasedScene, {{"effects", "[\"lubrication\", \"added_mass\", \"elastic\", \"gravity\"]"}});
  const model::PairGeometry p(fall);
  const double g = 9.81 * (1 - fall.fluid->density / fall.spheres[0].density);
  EXPECT_NEAR(model::impact_speed_bound(fall, p), std::sqrt(2 * g * p.initial_gap), 1e-12);
  // With drag: no faster than the terminal speed, which lies below the free fall over 2 D.
  const Scene dragged = load_scene(data_dir() + kReleasedScene);
  const auto& s = dragged.spheres[0];
  const double law_free = std::sqrt(2 * g * p.initial_gap);
  const double u_t = contact::terminal_speed(s.diameter, s.density, dragged.fluid->density, dragged.fluid->viscosity, 9.81,
                                             [](double re) { return contact::drag_factor(DragLaw::schiller_naumann, re); });
  EXPECT_NEAR(model::impact_speed_bound(dragged, model::PairGeometry(dragged)), std::min(law_free, u_t), 1e-12);
}

TEST(ImpactMemory, AReleasedSphereRemembersDownToItsImpact) {
  const Scene sc = load_scene(data_dir() + kReleasedScene);
  const model::CollisionModel m(sc);
  const model::PairGeometry& p = m.geometry();
  const double u = model::impact_speed_bound(sc, p);
  const double t_c = contact::hertz_contact_time(p.m_star, u, p.E_star, p.a_star);
  const double min_lag = choice_of(m, "history.min_lag_s");
  EXPECT_LE(min_lag, 1e-3 * t_c * (1 + 1e-12));
  EXPECT_LE(min_lag, 1e-3 * p.delta_ss_m / u * (1 + 1e-12));
  // Converged in min_lag: ten times shorter moves e by less than 1e-7; the memory of a sphere taken to approach at
  // 1 mm/s (min_lag 1e-3 δ_SS/(1 mm/s)) misses it by more than 1e-4.
  const double e = released_e({});
  std::ostringstream shorter, old;
  shorter << min_lag / 10;
  old << 1e-3 * p.delta_ss_m / 1e-3;
  EXPECT_NEAR(released_e({{"history.min_lag", shorter.str()}}), e, 1e-7);
  EXPECT_GT(std::abs(released_e({{"history.min_lag", old.str()}}) - e), 1e-4);
}
