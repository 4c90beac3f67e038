// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The fast modes of the soe-step evaluator (contact/history_force.hpp) at a lag Δ [s]: those with x = λ_i Δ > 40,
// whose e^(−x) is below rounding. For them e = 0 and M_ij = ∫_0^Δ σ^j e^(−λ_i (Δ−σ)) dσ [s^(j+1)] follows
// M_0 = 1/λ, M_j = (Δ^j − j M_(j−1))/λ, a polynomial in Δ; so their weighted sums
//   Σ_(i fast) w_i M_ij(Δ) = F_0^(j),  F_q^(0) = ρ_(q+1),  F_q^(j) = Δ^j ρ_(q+1) − j F_(q+1)^(j−1),
// come from the suffix sums ρ_q = Σ_(i fast) w_i λ_i^(−q), with no work per mode.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace imcol::contact {

class SoeFastModes {
 public:
  static constexpr int kPoints = 3;    // M_j for j < kPoints
  static constexpr double kFast = 40;  // fast: λΔ > kFast (e^(−40) = 4e-18)

  SoeFastModes() = default;
  /// rates λ_i [1/s] ascending, weights w_i (fixed).
  SoeFastModes(std::span<const double> rates, std::span<const double> w);
  /// The first fast mode at Δ.
  std::size_t first(double dt) const;
  /// Σ_(i ≥ first) w_i M_ij(Δ), j < kPoints.
  std::array<double, kPoints> sums(double dt, std::size_t first) const;

 private:
  std::vector<double> rate_;
  std::vector<double> rho_;  // ρ_q over the modes from s at [s · (kPoints + 1) + q]
};

}  // namespace imcol::contact
