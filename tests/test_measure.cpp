// SPDX-License-Identifier: BSD-3-Clause
// Measurements: continuous least-squares fits, restitution and Stokes numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/measure.hpp"

using namespace imcol;

TEST(Measure, ContinuousFitIsExactForALine) {
  std::vector<double> t, z;
  for (int i = 0; i <= 37; ++i) {
    t.push_back(0.01 * i * i);  // uneven sampling
    z.push_back(0.3 - 2.5 * t.back());
  }
  auto f = fit_line_continuous(t, z, 0.123, 7.9);
  ASSERT_TRUE(f);
  EXPECT_NEAR(f->slope, -2.5, 1e-12);
  EXPECT_NEAR(f->intercept, 0.3, 1e-12);
}

TEST(Measure, ContinuousFitOfAParabola) {
  // Least-squares slope of t² on [0, 1] is 12 ∫(t − ½) t² dt = 1; the interpolant's error is O(dt²).
  std::vector<double> t, z;
  const int n = 1000;
  for (int i = 0; i <= n; ++i) {
    t.push_back(double(i) / n);
    z.push_back(t.back() * t.back());
  }
  auto f = fit_line_continuous(t, z, 0.0, 1.0);
  ASSERT_TRUE(f);
  EXPECT_NEAR(f->slope, 1.0, 1e-6);
  // Moving the window end smoothly moves the slope smoothly (no jumps as samples enter).
  double prev = fit_line_continuous(t, z, 0.0, 0.5)->slope;
  for (int k = 1; k <= 100; ++k) {
    const double s = fit_line_continuous(t, z, 0.0, 0.5 + 1e-5 * k)->slope;
    EXPECT_LT(std::abs(s - prev), 2e-5);
    prev = s;
  }
  EXPECT_FALSE(fit_line_continuous(t, z, -0.1, 0.5));  // window not covered
}

TEST(Measure, HermiteFitReproducesAParabolaAndIgnoresTheSampling) {
  // z = 0.2 − 1.5 t + 4 t²: the parabola comes back exactly (slope and acceleration at any t_ref), and a line fit's
  // slope is the mean velocity over the window.
  auto z = [](double t) { return 0.2 - 1.5 * t + 4 * t * t; };
  auto u = [](double t) { return -1.5 + 8 * t; };
  std::vector<double> t, zs, us;
  for (int i = 0; i <= 23; ++i) {
    t.push_back(0.003 * i * i);
    zs.push_back(z(t.back()));
    us.push_back(u(t.back()));
  }
  auto p = fit_polynomial_hermite(t, zs, us, 0.05, 0.9, 2, 0.9);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->value, z(0.9), 1e-13);
  EXPECT_NEAR(p->slope, u(0.9), 1e-12);
  EXPECT_NEAR(p->accel, 8.0, 1e-10);
  auto l = fit_polynomial_hermite(t, zs, us, 0.05, 0.9, 1, 0.0);
  ASSERT_TRUE(l);
  EXPECT_NEAR(l->slope, (z(0.9) - z(0.05)) / 0.85, 1e-12);
  EXPECT_DOUBLE_EQ(l->accel, 0.0);
  // A cubic: the interpolant is exact, so two samplings give the same fit.
  auto c = [](double x) { return x * x * x - 0.3 * x; };
  auto cu = [](double x) { return 3 * x * x - 0.3; };
  std::vector<double> t1, z1, u1, t2, z2, u2;
  for (int i = 0; i <= 7; ++i) t1.push_back(i / 7.0);
  for (int i = 0; i <= 300; ++i) t2.push_back(std::sqrt(i / 300.0));
  for (double x : t1) z1.push_back(c(x)), u1.push_back(cu(x));
  for (double x : t2) z2.push_back(c(x)), u2.push_back(cu(x));
  auto a = fit_polynomial_hermite(t1, z1, u1, 0.1, 0.95, 2, 0.1), b = fit_polynomial_hermite(t2, z2, u2, 0.1, 0.95, 2, 0.1);
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(a->slope, b->slope, 1e-12);
  EXPECT_NEAR(a->accel, b->accel, 1e-10);
  EXPECT_FALSE(fit_polynomial_hermite(t1, z1, u1, -0.1, 0.5, 2, 0.0));  // window not covered
}

TEST(Measure, RestitutionAndStokes) {
  EXPECT_DOUBLE_EQ(restitution(1.0, 0.0, -0.8, 0.0), 0.8);
  EXPECT_DOUBLE_EQ(restitution(0.5, -0.5, 0.1, 0.5), 0.4);
  // St = m U/(6π μ a²) = (2/9)(ρ_p/ρ_f)(ρ_f a U/μ)... = (1/9)(ρ_p/ρ_f) Re for a sphere.
  const double a = 0.005, rho = 2500, mu = 0.01, U = 0.2, rho_f = 1000;
  const double m = rho * 4.0 / 3.0 * M_PI * a * a * a;
  const double Re = rho_f * 2 * a * U / mu;
  EXPECT_NEAR(stokes_number(m, U, mu, a), rho / rho_f * Re / 9, 1e-12);
}
