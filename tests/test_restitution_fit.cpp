// SPDX-License-Identifier: BSD-3-Clause
// The fit of e(St) = e_dry f(St_c/St) (run/restitution_fit.hpp): recovery from synthetic data, with and without noise;
// the samples it leaves out (e = 0, no e); too few samples.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "run/restitution_fit.hpp"

using imcol::run::fit_restitution;
using imcol::run::RestitutionFit;
using imcol::run::RestitutionForm;
using imcol::run::RestitutionSample;

namespace {

/// 15 Stokes numbers from 8 to 2000, log-spaced (a sweep's shape), e from the form at St_c, e_dry plus N(0, sigma) noise.
std::vector<RestitutionSample> synthetic(RestitutionForm form, double St_c, double e_dry, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<RestitutionSample> s;
  for (int i = 0; i < 15; ++i) {
    const double St = 8 * std::pow(2000.0 / 8, i / 14.0);
    const double e = imcol::run::restitution_model(form, St_c, e_dry, St);
    if (e < 0.02) continue;  // below the noise: a sweep would see no rebound there
    s.push_back({St, std::max(1e-3, e + (sigma > 0 ? noise(rng) : 0.0))});
  }
  return s;
}

}  // namespace

TEST(RestitutionFit, RecoversStcAndEdryFromExactData) {
  for (const auto form : {RestitutionForm::exponential, RestitutionForm::linear}) {
    const auto s = synthetic(form, 20, 0.9, 0, 1);
    const RestitutionFit free = fit_restitution(s, form);
    EXPECT_NEAR(free.St_c, 20, 1e-6) << to_string(form);
    EXPECT_NEAR(free.e_dry, 0.9, 1e-8) << to_string(form);
    EXPECT_LT(free.max_residual, 1e-8) << to_string(form);
    EXPECT_TRUE(free.e_dry_free);
    const RestitutionFit fixed = fit_restitution(s, form, 0.9);
    EXPECT_NEAR(fixed.St_c, 20, 1e-6) << to_string(form);
    EXPECT_EQ(fixed.e_dry, 0.9);
    EXPECT_FALSE(fixed.e_dry_free);
    EXPECT_EQ(fixed.used, s.size());
    EXPECT_EQ(fixed.St_min, s.front().St);
    EXPECT_EQ(fixed.St_max, s.back().St);
  }
}

TEST(RestitutionFit, RecoversStcAndEdryFromNoisyData) {
  // Noise sigma = 0.01 in e. Over 2000 noisy draws of these samples, the least-squares estimates scatter with standard
  // deviations 0.32 (exp) and 0.23 (linear) in St_c = 20 and 0.004 in e_dry = 0.9: the bounds are 4 of them, and the
  // reported standard errors must be of that size.
  for (const auto form : {RestitutionForm::exponential, RestitutionForm::linear}) {
    const bool expo = form == RestitutionForm::exponential;
    for (unsigned seed : {1u, 2u, 3u}) {
      const auto s = synthetic(form, 20, 0.9, 0.01, seed);
      const RestitutionFit f = fit_restitution(s, form);
      EXPECT_NEAR(f.St_c, 20, expo ? 1.3 : 0.93) << to_string(form) << " seed " << seed;
      EXPECT_NEAR(f.e_dry, 0.9, 0.016) << to_string(form) << " seed " << seed;
      EXPECT_GT(f.St_c_std_error, 0.1) << to_string(form);
      EXPECT_LT(f.St_c_std_error, 0.6) << to_string(form);
      EXPECT_GT(f.e_dry_std_error, 0.002) << to_string(form);
      EXPECT_LT(f.e_dry_std_error, 0.008) << to_string(form);
      // The residual is the noise: rms near sigma (13 or 12 samples, 2 parameters).
      EXPECT_GT(f.rms_residual, 0.004);
      EXPECT_LT(f.rms_residual, 0.016);
      // e_dry fixed to its true value: St_c within the same bound.
      const RestitutionFit fixed = fit_restitution(s, form, 0.9);
      EXPECT_NEAR(fixed.St_c, 20, expo ? 1.3 : 0.93);
    }
  }
}

TEST(RestitutionFit, LeavesOutNoReboundAndFailedPointsAndCountsThem) {
  auto s = synthetic(RestitutionForm::exponential, 20, 0.9, 0.01, 7);
  const RestitutionFit base = fit_restitution(s, RestitutionForm::exponential);
  auto with = s;
  with.push_back({3.0, 0.0});              // no rebound
  with.push_back({5.5, 0.0});              // no rebound
  with.push_back({NAN, std::nullopt});     // a failed run: no St either
  with.push_back({40.0, std::nullopt});    // ran, e not measured
  const RestitutionFit f = fit_restitution(with, RestitutionForm::exponential);
  EXPECT_EQ(f.St_c, base.St_c);
  EXPECT_EQ(f.e_dry, base.e_dry);
  EXPECT_EQ(f.used, s.size());
  EXPECT_EQ(f.no_rebound, 2u);
  EXPECT_EQ(f.without_e, 2u);
  ASSERT_TRUE(f.St_no_rebound_max);
  EXPECT_EQ(*f.St_no_rebound_max, 5.5);
  EXPECT_EQ(f.St_min, base.St_min);  // the range of validity is that of the points used
}

TEST(RestitutionFit, RejectsTooFewPointsWithACount) {
  const std::vector<RestitutionSample> two = {{10, 0.3}, {100, 0.8}, {4, 0.0}, {NAN, std::nullopt}};
  try {
    fit_restitution(two, RestitutionForm::exponential);
    FAIL() << "two points with e > 0 fitted two parameters";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("at least 3 points with e > 0; there are 2 (1 with e = 0, 1 failed or without e)"), std::string::npos) << m;
  }
  // With e_dry fixed, one parameter: two points do.
  EXPECT_NO_THROW(fit_restitution(two, RestitutionForm::exponential, 0.97));
  EXPECT_THROW(fit_restitution({{10, 0.3}}, RestitutionForm::linear, 0.97), std::invalid_argument);
  EXPECT_THROW(fit_restitution({{10, 0.3}, {-1, 0.5}, {100, 0.8}}, RestitutionForm::linear), std::invalid_argument);
  EXPECT_THROW(fit_restitution(two, RestitutionForm::linear, 1.5), std::invalid_argument);
}
