// SPDX-License-Identifier: BSD-3-Clause
// The soe-step evaluator's fast modes in closed form (contact/soe_fast_modes.hpp) against the modes one by one.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/history_kernel.hpp"
#include "contact/soe_fast_modes.hpp"

namespace {

using imcol::contact::SoeFastModes;

// M_j = ∫_0^Δ (Δ − s)^j e^(−λs) ds = Σ_k C(j,k) Δ^(j−k) (−1)^k G_k, G_k = ∫_0^Δ s^k e^(−λs) ds
//     = k!/λ^(k+1) (1 − e^(−x) Σ_(m≤k) x^m/m!), x = λΔ: exact, and free of cancellation for x > 40.
long double fast_mode_integral(long double lam, long double dt, int j) {
  const long double x = lam * dt;
  long double M = 0, binom = 1;
  for (int k = 0; k <= j; ++k) {
    long double term = 1, partial = 1, fact = 1;
    for (int m = 1; m <= k; ++m) {
      term *= x / m;
      partial += term;
      fact *= m;
    }
    const long double G = fact / std::pow(lam, k + 1) * (1 - std::exp(-x) * partial);
    M += binom * std::pow(dt, j - k) * ((k % 2) ? -G : G);
    binom = binom * (j - k) / (k + 1);
  }
  return M;
}

TEST(SoeFastModes, SumsMatchTheModesOneByOne) {
  const auto soe = imcol::contact::inverse_sqrt_soe(6.5e-8, 0.06, 1e-6);
  const SoeFastModes fast(soe.rate, soe.weight);
  const std::size_t n = soe.rate.size();
  for (double dt : {1e-8, 3e-7, 1e-6, 2.5e-5, 1e-4, 7.9e-4, 0.01, 1.0}) {
    const std::size_t first = fast.first(dt);
    // The first fast mode is the first with λΔ > 40.
    if (first < n) {
      EXPECT_GT(soe.rate[first] * dt, SoeFastModes::kFast) << dt;
    }
    if (first > 0) {
      EXPECT_LE(soe.rate[first - 1] * dt, SoeFastModes::kFast) << dt;
    }
    const auto sums = fast.sums(dt, first);
    for (int j = 0; j < SoeFastModes::kPoints; ++j) {
      long double ref = 0;
      for (std::size_t i = first; i < n; ++i) ref += soe.weight[i] * fast_mode_integral(soe.rate[i], dt, j);
      if (first == n) {
        EXPECT_EQ(sums[j], 0.0) << "dt " << dt << " j " << j;
      } else {
        EXPECT_NEAR(sums[j] / static_cast<double>(ref), 1.0, 1e-13) << "dt " << dt << " j " << j;
      }
    }
  }
}

TEST(SoeFastModes, EveryModeFastAtALongLag) {
  const auto soe = imcol::contact::inverse_sqrt_soe(1e-6, 1.0, 1e-6);
  const SoeFastModes fast(soe.rate, soe.weight);
  const double long_lag = 41 / soe.rate.front();  // s: λ_min Δ = 41
  EXPECT_EQ(fast.first(long_lag), 0u);
  EXPECT_EQ(fast.first(1e-9), soe.rate.size());  // none
  // All modes fast: Σ w_i M_0 = Σ w_i/λ_i.
  double inv = 0;
  for (std::size_t i = 0; i < soe.rate.size(); ++i) inv += soe.weight[i] / soe.rate[i];
  EXPECT_NEAR(fast.sums(long_lag, 0)[0] / inv, 1.0, 1e-14);
}

}  // namespace
