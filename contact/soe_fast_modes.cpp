// SPDX-License-Identifier: BSD-3-Clause
#include "contact/soe_fast_modes.hpp"

#include <algorithm>

namespace imcol::contact {

namespace {
constexpr int kQ = SoeFastModes::kPoints + 1;  // ρ_q for q ≤ kPoints
}

SoeFastModes::SoeFastModes(std::span<const double> rates, std::span<const double> w) : rate_(rates.begin(), rates.end()) {
  const std::size_t n = rate_.size();
  rho_.assign((n + 1) * kQ, 0.0);
  for (std::size_t i = n; i-- > 0;) {
    double v = w[i];
    for (int q = 0; q < kQ; ++q, v /= rate_[i]) rho_[i * kQ + q] = rho_[(i + 1) * kQ + q] + v;
  }
}

std::size_t SoeFastModes::first(double dt) const {
  return static_cast<std::size_t>(std::upper_bound(rate_.begin(), rate_.end(), kFast / dt) - rate_.begin());
}

std::array<double, SoeFastModes::kPoints> SoeFastModes::sums(double dt, std::size_t first) const {
  constexpr int top = kPoints - 1;
  const double* rho = &rho_[first * kQ];
  std::array<double, kPoints> f{}, out{};
  for (int q = 0; q <= top; ++q) f[q] = rho[q + 1];
  out[0] = f[0];
  double dj = 1;  // Δ^j
  for (int j = 1; j <= top; ++j) {
    dj *= dt;
    for (int q = 0; q <= top - j; ++q) f[q] = dj * rho[q + 1] - j * f[q + 1];
    out[j] = f[0];
  }
  return out;
}

}  // namespace imcol::contact
