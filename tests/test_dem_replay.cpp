// SPDX-License-Identifier: BSD-3-Clause
// The replay of LIGGGHTS's hooke normal contact (study/dem_replay.hpp), the table lookup (study/dem_lookup.hpp) and
// the fit of CriticalStokes and MaximumRestitution through the replay (study/dem_replay_fit.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "contact/formulas.hpp"
#include "study/dem_lookup.hpp"
#include "study/dem_replay.hpp"
#include "study/dem_replay_fit.hpp"

using namespace imcol::study;

namespace {

/// A 2 mm glass bead on a steel wall (data/materials.csv), characteristicVelocity 1 m/s.
HookeContact dem_replay_glass_steel() {
  HookeContact c;
  c.m_eff = 2540 * M_PI * 0.002 * 0.002 * 0.002 / 6;
  c.r_eff = 0.001;
  c.Y_eff = imcol::contact::effective_modulus(60e9, 0.23, 190e9, 0.27);
  c.char_vel = 1.0;
  return c;
}

constexpr double kDemReplayMu = 0.006;  // Pa s

ViscousRule dem_replay_rule(double St_c, double e_max) { return ViscousRule{kDemReplayMu, St_c, e_max}; }

double dem_replay_e(double St, double St_c, double e_max, int steps = 1000) {
  const HookeContact c = dem_replay_glass_steel();
  ReplayStep s;
  s.steps_per_contact = steps;
  return replay_viscous(c, dem_replay_rule(St_c, e_max), impact_speed_for_stokes(c, kDemReplayMu, St), s).e;
}

/// First-order (small damping) estimate of the rule's e: the undamped contact v_n = −U cos θ, θ = ω t in [0, π],
/// loses 4 ∫ ζ(θ) cos²θ dθ of its kinetic energy, ζ = |L|/√(L² + π²), L = ln e_max + St_c / St(θ) with St(θ) =
/// −St0 cos θ (signed) or −St0 |cos θ| (the sign dropped). Midpoint rule on 200000 intervals.
double dem_replay_small_damping_e(double St0, double St_c, double e_max, bool signed_St) {
  const int n = 200000;
  double loss = 0;
  for (int i = 0; i < n; ++i) {
    const double th = (i + 0.5) * M_PI / n, cs = std::cos(th);
    const double St = signed_St ? -St0 * cs : -St0 * std::abs(cs);
    const double L = std::log(e_max) + St_c / St;
    loss += std::abs(L) / std::sqrt(L * L + M_PI * M_PI) * cs * cs * M_PI / n;
  }
  return std::sqrt(1 - 4 * loss);
}

}  // namespace

TEST(DemReplay, HookeStiffnessScalesAsItsFormula) {
  // Y* of glass on steel by hand; k_n ∝ Y*^(4/5) V_c^(2/5) m*^(1/5) r*^(2/5).
  EXPECT_NEAR(imcol::contact::effective_modulus(60e9, 0.23, 190e9, 0.27), 1 / ((1 - 0.0529) / 60e9 + (1 - 0.0729) / 190e9), 1e-3);
  HookeContact c = dem_replay_glass_steel();
  const double k = hooke_k_n(c);
  c.Y_eff *= 2;
  EXPECT_NEAR(hooke_k_n(c) / k, std::pow(2.0, 0.8), 1e-12);
  c = dem_replay_glass_steel();
  c.char_vel *= 10;
  EXPECT_NEAR(hooke_k_n(c) / k, std::pow(10.0, 0.4), 1e-12);
  c = dem_replay_glass_steel();
  EXPECT_NEAR(hooke_contact_time(c), M_PI * std::sqrt(c.m_eff / k), 1e-18);
}

TEST(DemReplay, WithoutDampingTheReboundKeepsTheImpactSpeed) {
  const HookeContact c = dem_replay_glass_steel();
  for (const double U : {0.01, 0.3, 2.0}) {
    const ReplayResult r = replay_constant_e(c, 1.0, U);
    EXPECT_TRUE(r.separated);
    EXPECT_NEAR(r.e, 1.0, 1e-7) << U;
    // The contact lasts the undamped half period, within a step.
    EXPECT_NEAR(r.duration, hooke_contact_time(c), 1.01 * r.dt) << U;
  }
}

TEST(DemReplay, ConstantRestitutionGivesTheSpringDashpotsClosedForm) {
  // γ_n = 2 √(m* k_n) (−ln e) / √(π² + ln² e): the velocity ratio at δ = 0 is e (separation error O(Δt)).
  const HookeContact c = dem_replay_glass_steel();
  for (const double e : {0.95, 0.7, 0.4, 0.1}) {
    EXPECT_NEAR(replay_constant_e(c, e, 0.5).e, e, 1e-3) << e;
    ReplayStep fine;
    fine.steps_per_contact = 20000;
    EXPECT_NEAR(replay_constant_e(c, e, 0.5, fine).e, e, 5e-5) << e;
  }
  // e = 0: critical damping, no return within 60 contact times.
  const ReplayResult zero = replay_constant_e(c, 0.0, 0.5);
  EXPECT_FALSE(zero.separated);
  EXPECT_EQ(zero.e, 0.0);
}

TEST(DemReplay, ViscousRuleConvergesWithTheStepAtFirstOrder) {
  const double e250 = dem_replay_e(30, 8, 0.8, 250), e1000 = dem_replay_e(30, 8, 0.8, 1000), e4000 = dem_replay_e(30, 8, 0.8, 4000);
  const double e32000 = dem_replay_e(30, 8, 0.8, 32000);
  EXPECT_LT(std::abs(e1000 - e32000), 5e-4);  // the export's step (1000 per contact)
  EXPECT_LT(std::abs(e4000 - e32000), std::abs(e1000 - e32000));
  EXPECT_LT(std::abs(e1000 - e32000), std::abs(e250 - e32000));
  // First order: a step 4 times smaller leaves about a quarter of the error (against the finest).
  const double ratio = std::abs(e250 - e32000) / std::abs(e1000 - e32000);
  EXPECT_GT(ratio, 2.5);
  EXPECT_LT(ratio, 6.0);
}

TEST(DemReplay, LogRestitutionTurnsPositiveOnTheReboundAndDampingStaysPositive) {
  // LIGGGHTS's convention: v_n < 0 approaching. St_c = 2, e_max = 0.9, |St| = 10.
  const HookeContact c = dem_replay_glass_steel();
  const ViscousRule rule = dem_replay_rule(2, 0.9);
  const double v10 = impact_speed_for_stokes(c, kDemReplayMu, 10);
  EXPECT_NEAR(viscous_stokes(c, kDemReplayMu, -v10), -10, 1e-12);
  EXPECT_NEAR(viscous_log_e(c, rule, -v10), std::log(0.9) - 0.2, 1e-12);  // approach: −0.305
  EXPECT_NEAR(viscous_log_e(c, rule, v10), std::log(0.9) + 0.2, 1e-12);   // rebound: +0.095, "e" = 1.10
  const double k = hooke_k_n(c), Lr = std::log(0.9) + 0.2;
  EXPECT_NEAR(hooke_gamma_n(c.m_eff, k, Lr), std::sqrt(4 * c.m_eff * k * Lr * Lr / (Lr * Lr + M_PI * M_PI)), 1e-15);
  EXPECT_GT(hooke_gamma_n(c.m_eff, k, Lr), 0);
  // No damping where L = 0 on the rebound: |St| = St_c / (−ln e_max); critical damping at v_n = 0.
  const double v0 = impact_speed_for_stokes(c, kDemReplayMu, 2 / -std::log(0.9));
  EXPECT_NEAR(hooke_gamma_n(c.m_eff, k, viscous_log_e(c, rule, v0)), 0, 1e-9 * std::sqrt(c.m_eff * k));
  EXPECT_EQ(hooke_gamma_n(c.m_eff, k, viscous_log_e(c, rule, 0.0)), std::sqrt(4 * c.m_eff * k));
}

TEST(DemReplay, ViscousRuleMatchesTheSmallDampingEstimateWithTheSignedStokesNumber) {
  // St0 = 1000, St_c = 5, e_max = 0.99: ζ ≈ 0.003–0.01. The signed St (weaker damping on the rebound) gives
  // e = 0.98962 to first order; dropping the sign would give 0.98345.
  const double e = dem_replay_e(1000, 5, 0.99, 4000);
  const double signed_estimate = dem_replay_small_damping_e(1000, 5, 0.99, true);
  const double unsigned_estimate = dem_replay_small_damping_e(1000, 5, 0.99, false);
  EXPECT_NEAR(e, signed_estimate, 5e-4);
  EXPECT_GT(std::abs(e - unsigned_estimate), 5e-3);
  // The rebound's weaker damping lets e exceed e_max slightly here.
  EXPECT_GT(dem_replay_e(200, 1, 0.97, 4000), 0.97);
}

TEST(DemReplay, ViscousRuleIsIndependentOfStiffnessAtAFixedStepsPerContact) {
  // m* v' = −k δ − γ(St(v)) v with γ ∝ √(m* k): in units of U and 1/ω only St is left.
  const double St = 30, U = impact_speed_for_stokes(dem_replay_glass_steel(), kDemReplayMu, St);
  const double base = replay_viscous(dem_replay_glass_steel(), dem_replay_rule(8, 0.8), U).e;
  for (const double f : {1e-3, 0.1, 100.0}) {
    HookeContact c = dem_replay_glass_steel();
    c.Y_eff *= f;
    c.char_vel /= f;
    EXPECT_NEAR(replay_viscous(c, dem_replay_rule(8, 0.8), U).e, base, 1e-9) << f;
  }
}

TEST(DemLookup, InterpolatesLinearlyInLnStAndClampsAtTheEnds) {
  const std::vector<RestitutionRow> rows{{5, 0}, {10, 0}, {20, 0.4}, {40, 0.6}, {80, 0.7}};
  EXPECT_EQ(lookup_restitution(rows, 20), 0.4);
  EXPECT_EQ(lookup_restitution(rows, 40), 0.6);
  EXPECT_NEAR(lookup_restitution(rows, std::sqrt(20.0 * 40.0)), 0.5, 1e-14);  // midway in ln St
  EXPECT_EQ(lookup_restitution(rows, 15), 0.0);   // below the first row with e > 0
  EXPECT_EQ(lookup_restitution(rows, 1), 0.0);
  EXPECT_EQ(lookup_restitution(rows, 500), 0.7);  // above the last row
  EXPECT_THROW(lookup_restitution({}, 1), std::invalid_argument);
}

TEST(DemLookup, ConstantRestitutionReplayReproducesTheTable) {
  // A restitution table as dem_table.csv writes it: St at first touch, e looked up, γ_n for that e.
  const std::vector<RestitutionRow> rows{{7.05861919494, 0},          {9.87627499744, 0},          {13.517575973, 0.229848282776},
                                         {18.2188536209, 0.41757035805}, {32.1182261898, 0.643567607842}, {92.3312362105, 0.843161975215}};
  const HookeContact c = dem_replay_glass_steel();
  ReplayStep fine;
  fine.steps_per_contact = 20000;
  for (const auto& r : rows) {
    const double e = lookup_restitution(rows, r.St);
    EXPECT_EQ(e, r.e);
    EXPECT_NEAR(replay_constant_e(c, e, impact_speed_for_stokes(c, kDemReplayMu, r.St), fine).e, r.e, 5e-5) << r.St;
  }
}

TEST(DemReplayFit, RecoversTheRulesParametersFromItsOwnReplay) {
  const HookeContact c = dem_replay_glass_steel();
  const std::vector<double> St{12, 16, 22, 30, 45, 70, 100, 150};
  const std::vector<double> e = replayed_restitution(c, dem_replay_rule(5, 0.9), St);
  std::vector<ReplaySample> samples;
  for (std::size_t i = 0; i < St.size(); ++i) samples.push_back({St[i], e[i]});
  const ReplayFit f = fit_viscous_rule(samples, c, kDemReplayMu);
  EXPECT_NEAR(f.rule.critical_stokes, 5, 0.01);
  EXPECT_NEAR(f.rule.maximum_restitution, 0.9, 1e-3);
  EXPECT_LT(f.max_residual, 1e-4);
  EXPECT_TRUE(f.e_max_free);
  const ReplayFit fixed = fit_viscous_rule(samples, c, kDemReplayMu, 0.9);
  EXPECT_NEAR(fixed.rule.critical_stokes, 5, 0.01);
  EXPECT_EQ(fixed.rule.maximum_restitution, 0.9);
  EXPECT_FALSE(fixed.e_max_free);
  EXPECT_THROW(fit_viscous_rule({{10, 0.5}, {20, 0.6}}, c, kDemReplayMu), std::invalid_argument);
}

TEST(DemReplay, LimitForceRemovesTheAttractionAtTheEndOfAContact) {
  // Without limitForce, F_n = k δ − γ v_n < 0 late in the rebound slows the sphere; with it, F_n >= 0: e is higher.
  const HookeContact c = dem_replay_glass_steel();
  ReplayStep on;
  on.limit = ForceLimit::on;
  for (const double e : {0.8, 0.3}) {
    const double off_e = replay_constant_e(c, e, 0.5).e, on_e = replay_constant_e(c, e, 0.5, on).e;
    EXPECT_NEAR(off_e, e, 1e-3);
    EXPECT_GT(on_e, off_e + 1e-3) << e;
  }
}
