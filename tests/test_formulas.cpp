// SPDX-License-Identifier: BSD-3-Clause
// Layer 1: formulas and identities (MODEL.md §2.1, 2.2, 2.4, 2.5).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "contact/formulas.hpp"
#include "contact/table_data.hpp"

using namespace imcol;
using namespace imcol::contact;

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
// Steel sphere, D = 12.7 mm, on a steel sphere: typical seed parameters.
constexpr double a = 6.35e-3, rho = 7780, E = 190e9, nu = 0.27;
const double m = rho * 4.0 / 3.0 * pi * a * a * a;

double simpson(const std::function<double(double)>& f, double x0, double x1, int n) {
  const double h = (x1 - x0) / n;
  double s = f(x0) + f(x1);
  for (int i = 1; i < n; ++i) s += f(x0 + i * h) * (i % 2 ? 4 : 2);
  return s * h / 3;
}
}  // namespace

TEST(Hertz, EnergyBalanceStoresTheKineticEnergy) {
  for (double U : {0.01, 0.1, 1.0}) {
    const double Es = effective_modulus(E, nu, E, nu), as = reduced(a, a), ms = reduced(m, m);
    const double emax = hertz_max_indentation(ms, U, Es, as);
    // ∫_0^εmax W dε with the substitution ε = s², smooth integrand.
    const double work = simpson([&](double s) { return hertz_force(Es, as, s * s) * 2 * s; }, 0, std::sqrt(emax), 2000);
    EXPECT_NEAR(work / (0.5 * ms * U * U), 1.0, 1e-10) << "U = " << U;
  }
}

TEST(Hertz, ContactTimeMatchesIntegratedImpact) {
  // Integrate m ε'' = −W(ε) from ε = 0, ε' = U until ε returns to 0 (RK4, small step).
  const double Es = effective_modulus(E, nu, E, nu), U = 0.1;
  const double tc = hertz_contact_time(m, U, Es, a);
  double x = 0, v = U, t = 0;
  const double h = tc / 200000;
  auto acc = [&](double xx) { return -hertz_force(Es, a, xx) / m; };
  double xmax = 0;
  while (true) {
    const double k1x = v, k1v = acc(x);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x);
    const double xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (xn < 0) {
      t += h * x / (x - xn);
      break;
    }
    x = xn;
    t += h;
    xmax = std::max(xmax, x);
  }
  EXPECT_NEAR(t / tc, 1.0, 1e-3);
  EXPECT_NEAR(xmax / hertz_max_indentation(m, U, Es, a), 1.0, 1e-6);
  EXPECT_NEAR(-v / U, 1.0, 1e-6);  // elastic: rebound speed equals impact speed
}

TEST(Hertz, LargeTargetTendsToTheWall) {
  // a2 → ∞: a* → a1, c_log → a1/5; m2 → ∞: m* → m1.
  EXPECT_NEAR(reduced(a, 1e9 * a) / a, 1.0, 1e-8);
  EXPECT_DOUBLE_EQ(reduced(a, inf), a);
  EXPECT_NEAR(lubrication_log_coefficient(a, 1e9 * a) / (a / 5), 1.0, 1e-7);
  EXPECT_DOUBLE_EQ(lubrication_log_coefficient(a, inf), a / 5);
  const double Es = effective_modulus(E, nu, E, nu);
  EXPECT_NEAR(hertz_peak_force(reduced(m, 1e12 * m), 0.1, Es, reduced(a, 1e12 * a)) / hertz_peak_force(m, 0.1, Es, a), 1.0, 1e-9);
}

TEST(Hertz, EffectiveModulus) {
  EXPECT_NEAR(effective_modulus(E, nu, E, nu), E / (2 * (1 - nu * nu)), 1e-6 * E);
  EXPECT_NEAR(effective_modulus(E, nu, 1e30, 0.3), E / (1 - nu * nu), 1e-6 * E);
}

TEST(Lubrication, BrennerSeriesReferenceValues) {
  EXPECT_NEAR(brenner_lambda_series(0.01), 101.90, 0.005);
  EXPECT_NEAR(brenner_lambda_series(0.1), 11.46, 0.005);
  EXPECT_NEAR(brenner_lambda_series(1.0), 2.126, 0.0005);
  // Far field: λ → 1 + (9/8)(a/z) for a centre at distance z = a + h.
  const double h = 1e3;
  EXPECT_NEAR(brenner_lambda_series(h) - 1, 9.0 / 8 / (1 + h), 2e-3 * 9.0 / 8 / (1 + h));
}

TEST(Lubrication, BrennerFastMatchesSeries) {
  for (double d : {2e-5, 1e-4, 3.3e-3, 0.07, 0.3, 1.0, 7.0, 500.0, 2e3})
    EXPECT_NEAR(brenner_lambda(d) / brenner_lambda_series(d), 1.0, 1e-8) << "h/a = " << d;
  // Below the table the asymptote is used; it stays continuous and close to the series.
  EXPECT_NEAR(brenner_lambda(5e-6) / brenner_lambda_series(5e-6), 1.0, 1e-9);
}

TEST(Lubrication, BrennerSmallGapAsymptote) {
  // Cox & Brenner (1967): λ = a/h + (1/5) ln(a/h) + 0.971 + O(h ln h).
  for (double d : {1e-3, 1e-4, 1e-5}) {
    const double asym = 1 / d + 0.2 * std::log(1 / d) + 0.971264;
    EXPECT_NEAR(brenner_lambda_series(d), asym, 20 * d * std::log(1 / d)) << d;
  }
}

TEST(Lubrication, AsymptoticLawLimits) {
  const double as = a / 2, c = lubrication_log_coefficient(a, a), hc = as;
  EXPECT_DOUBLE_EQ(asymptotic_resistance(hc, as, c, hc), 0.0);
  EXPECT_DOUBLE_EQ(asymptotic_resistance(2 * hc, as, c, hc), 0.0);
  // Leading term a*²/h dominates at small gaps.
  const double h = 1e-6 * as;
  EXPECT_NEAR(asymptotic_resistance(h, as, c, hc) / (as * as / h), 1.0, 1e-4);
  // Symmetric in the pair, equal spheres: c_log = a * 9/40 / 5... = a1 a2 (9 a²)/(5 (2a)³) = 9a/40.
  EXPECT_DOUBLE_EQ(lubrication_log_coefficient(a, 2 * a), lubrication_log_coefficient(2 * a, a));
  EXPECT_NEAR(lubrication_log_coefficient(a, a), 9 * a / 40, 1e-15);
  // Wall limit of the asymptotic law against Brenner's series: a/h + (1/5) ln(a/h) + 0.971.
  const double d = 1e-4, H = 1e6 * a;  // a large h_c; undo its shift
  const double unshifted = asymptotic_resistance(d * a, a, a / 5, H) + a * a / H - (a / 5) * std::log(H / a);
  EXPECT_NEAR(unshifted / a, brenner_lambda_series(d) - 0.971264, 1e-3);
}

TEST(Lubrication, SeedLawForAnEqualPairIsTwiceTheExactAsymptote) {
  // The seed's 6πμ a (λ(h/a*) − 1) against the leading two-sphere term 6πμ a*²/h: the ratio tends to 2 as h → 0
  // (at h/a* = 1e-4 it is 2 (1 + (1/5) 1e-4 ln 1e4 + ...) = 2.0004).
  const double as = a / 2;
  const GapGeometry g{a, a, as, lubrication_log_coefficient(a, a), as};
  const double h = 1e-4 * as;
  const GapResistance seed = gap_resistance(LubricationModel::seed, g, h);
  EXPECT_NEAR(seed.on1 / (as * as / h), 2.0, 1e-3);
  EXPECT_DOUBLE_EQ(seed.on1, seed.on2);  // equal radii: equal and opposite
  // The exact law's own ratio to its leading term is 1 there.
  const GapResistance exact = gap_resistance(LubricationModel::asymptotic, g, h);
  EXPECT_NEAR(exact.on1 / (as * as / h), 1.0, 1e-3);
  EXPECT_NEAR(seed.on1 / exact.on1, 2.0, 1e-3);
}

TEST(Lubrication, SeedLawForAWallIsBrenner) {
  const GapGeometry g{a, inf, a, a / 5, a};
  for (double d : {1e-5, 1e-3, 0.05, 1.0, 30.0}) {
    const GapResistance s = gap_resistance(LubricationModel::seed, g, d * a);
    EXPECT_DOUBLE_EQ(s.on1, gap_resistance(LubricationModel::brenner, g, d * a).on1) << d;
    EXPECT_DOUBLE_EQ(s.on1, a * (brenner_lambda(d) - 1)) << d;
  }
}

TEST(Lubrication, SeedLawOnUnequalSpheresDiffersByTheRadiusRatio) {
  const double a2 = 3 * a, as = reduced(a, a2);
  const GapGeometry g{a, a2, as, lubrication_log_coefficient(a, a2), as};
  for (double d : {1e-4, 0.02, 0.5}) {
    const GapResistance s = gap_resistance(LubricationModel::seed, g, d * as);
    EXPECT_NEAR(s.on2 / s.on1, a2 / a, 1e-14) << d;
    EXPECT_DOUBLE_EQ(s.on1, a * (brenner_lambda(d) - 1)) << d;
    const GapResistance x = gap_resistance(LubricationModel::asymptotic, g, d * as);
    EXPECT_DOUBLE_EQ(x.on1, x.on2) << d;  // the exact law is equal and opposite
  }
}

TEST(Lubrication, RegularisedGap) {
  const double hm = 1e-6;
  EXPECT_NEAR(regularised_gap(1e-3, hm), 1e-3, 1e-9);
  EXPECT_DOUBLE_EQ(regularised_gap(0, hm), hm);
  EXPECT_GT(regularised_gap(-1e-5, hm), 0);
  EXPECT_LT(regularised_gap(-1e-5, hm), hm);
}

TEST(AddedMass, ContactValueAndFarField) {
  EXPECT_NEAR(added_mass_W(0.0), 0.2021, 5e-5);
  EXPECT_NEAR(added_mass_W(1e-9), zeta3_minus_1, 1e-6);
  EXPECT_NEAR(added_mass_W_series(1e-6), zeta3_minus_1, 1e-4);
  EXPECT_NEAR(0.5 * (1 + 3 * added_mass_W(0.0)), 0.803, 5e-4);  // added-mass coefficient at contact
  for (double d : {10.0, 100.0, 2000.0}) {
    const double far = 1 / (8 * std::pow(1 + d, 3));
    EXPECT_NEAR(added_mass_W(d) / far, 1.0, 2e-3 * 10 / d) << d;
  }
}

TEST(AddedMass, FastMatchesSeriesAndDerivative) {
  for (double d : {1e-5, 1e-3, 0.05, 0.5, 5.0, 200.0}) {
    EXPECT_NEAR(added_mass_W(d) / added_mass_W_series(d), 1.0, 1e-7) << d;
    EXPECT_NEAR(added_mass_dW(d) / added_mass_dW_series(d), 1.0, 1e-5) << d;
    const double h = 1e-4 * d;
    const double fd = (added_mass_W_series(d + h) - added_mass_W_series(d - h)) / (2 * h);
    EXPECT_NEAR(added_mass_dW_series(d) / fd, 1.0, 1e-6) << d;
  }
  // dW/dδ diverges like ln δ at contact.
  EXPECT_LT(added_mass_dW(1e-5), added_mass_dW(1e-3));
  EXPECT_NEAR(added_mass_dW_series(1e-5) - added_mass_dW_series(1e-4), added_mass_dW_series(1e-4) - added_mass_dW_series(1e-3),
              0.05);
}

TEST(Ramp, EndValuesAndContinuation) {
  for (double beta : {1.0, 10.0, 200.0, 1e4}) {
    EXPECT_DOUBLE_EQ(ramp_F(1.0, beta), 0.0);
    EXPECT_NEAR(ramp_F(0.0, beta), 1.0, 1e-14);
    EXPECT_TRUE(std::isfinite(ramp_F(0.5, beta)));
    // Past contact: finite and growing, slope continuous at 0.
    EXPECT_GT(ramp_F(-0.01, beta), 1.0);
    EXPECT_GT(ramp_F(-1.0, beta), ramp_F(-0.01, beta));
    EXPECT_TRUE(std::isfinite(ramp_F(-1e3, beta)));
    const double h = 1e-7;
    const double left = (ramp_F(0.0, beta) - ramp_F(-h, beta)) / h, right = (ramp_F(h, beta) - ramp_F(0.0, beta)) / h;
    EXPECT_NEAR(left / right, 1.0, 1e-3);  // one-sided differences: O(βh) ≤ 1e-3
  }
  // Monotone decreasing on [0, 1].
  double prev = 2;
  for (int i = 0; i <= 100; ++i) {
    const double f = ramp_F(i / 100.0, 30.0);
    EXPECT_LE(f, prev);
    prev = f;
  }
}

TEST(Ramp, IntegralAndEnergyConsistentBeta) {
  for (double beta : {2.0, 30.0, 300.0})
    EXPECT_NEAR(simpson([&](double x) { return ramp_F(x, beta); }, 0, 1, 20000), ramp_F_integral(beta), 1e-9);
  for (double ratio : {0.01, 0.1, 0.4}) {
    const double dss = 1e-4, emax = ratio * dss;
    const double b = energy_consistent_beta(dss, emax);
    EXPECT_NEAR(dss * ramp_F_integral(b), 0.4 * emax, 1e-12 * dss);
  }
  EXPECT_NEAR(energy_consistent_beta(1e-4, 1e-7) / (2.5e-4 / 1e-7), 1.0, 1e-6);  // large-β limit 5δ_SS/(2ε_max)
  EXPECT_THROW(energy_consistent_beta(1e-4, 2e-4), std::domain_error);
}

TEST(Blend, EndValues) {
  EXPECT_DOUBLE_EQ(blend_H(0.0), 1.0);
  EXPECT_DOUBLE_EQ(blend_H(1.0), 0.5);
  EXPECT_DOUBLE_EQ(blend_H(2.0), 0.0);
  EXPECT_DOUBLE_EQ(blend_H(5.0), 0.0);
  EXPECT_DOUBLE_EQ(blend_H(-1.0), 1.0);
}

TEST(Drag, Laws) {
  EXPECT_DOUBLE_EQ(drag_factor(DragLaw::stokes, 100), 1.0);
  EXPECT_NEAR(drag_factor(DragLaw::schiller_naumann, 100), 4.5489, 1e-4);  // 1 + 0.15·100^0.687, evaluated independently
  EXPECT_DOUBLE_EQ(drag_factor(DragLaw::schiller_naumann, 0), 1.0);
}

TEST(Tables, ShippedNodesMatchTheSeries) {
  // contact/table_data.cpp holds the nodes imcol_gen_tables computed; recompute every one.
  using table_data::brenner_n;
  using table_data::w_n;
  for (int i = 0; i < w_n; ++i) {
    const auto v = table_node(TableKind::added_mass_W, i);
    EXPECT_NEAR(table_data::w_nodes[i][0] / v[0], 1.0, 1e-13) << i;
    EXPECT_NEAR(table_data::w_nodes[i][1] / v[1], 1.0, 1e-12) << i;
  }
  for (int i = 0; i < brenner_n; ++i) {
    const auto v = table_node(TableKind::brenner_lambda, i);
    EXPECT_NEAR(table_data::brenner_nodes[i][0] / v[0], 1.0, 1e-13) << i;
    EXPECT_NEAR(table_data::brenner_nodes[i][1] / v[1], 1.0, 1e-9) << i;  // central differences
  }
}
