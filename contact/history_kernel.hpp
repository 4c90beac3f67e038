// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// History (Basset-type) force kernels and their sum-of-exponentials approximation (MODEL.md §2.3).
//
//   f_H,m = −6πμ a_m K_H(δ**) ∫_0^t (dU_m/dτ) K(t − τ) dτ                                   [N]
//   K(s)  = {[4πνs/D²]^(1/(2c1)) + [π|U|³s²/(Dν f_H³)]^(1/c1)}^(−c1),  f_H = 0.75 + c2 Re   [-]
//         = K_B(s) φ(s/s_c),  K_B(s) = D/(2√(πνs)) (Basset),  φ(x) = (1 + x^(3/(2c1)))^(−c1),
//   s_c   = (2/√π)^(2/3) ν f_H²/U² = (2/√π)^(2/3) (D²/ν) (0.75/Re + c2)²                   [s]
// with Re = |U| D/ν. basset: c2 = 0 (s_c = ∞); mei-adrian (Mei & Adrian 1992) c1 = 2, c2 = 0.105;
// kim (Kim, Elghobashi & Sirignano 1998, without their acceleration factor) c1 = 2.5, c2 = 0.126;
// dorgan-loth (Dorgan & Loth 2007) c1 = 2.5, c2 = 0.2. Every kernel tends to K_B as Re → 0.
//
// Sum of exponentials (production evaluator): K(s) ≈ Σ_i w_i e^(−λ_i s) on [min_lag, horizon], with
// the rates of the McLean (2018) variant of the Beylkin–Monzón trapezoid rule for s^(−1/2):
//   u_n = n h, x_n = u_n − e^(−u_n), λ_n = e^(x_n)/T, w_n = h (1 + e^(−u_n)) e^(x_n/2)/√(π T),
// error ≈ 7 e^(−π²/h) relative. Short-lag correction κ = ∫_0^min_lag K ds − Σ w_i (1 − e^(−λ_i min_lag))/λ_i
// (an added-mass-like term κ dU/dt). Finite-Re kernels keep the rates; their weights are fitted
// (regularised least squares, relative error) and tabulated in ln s_c, so they vary smoothly with Re.
#include <complex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/choices.hpp"

namespace imcol::contact {


/// The kernel K(s; Re) of one sphere of diameter D [m] in a fluid of kinematic viscosity ν [m²/s].
class HistoryKernel {
 public:
  HistoryKernel(KernelKind kind, double D, double nu);
  KernelKind kind() const { return kind_; }
  double c1() const { return c1_; }
  double c2() const { return c2_; }
  double diameter() const { return D_; }
  double nu() const { return nu_; }
  /// s_c(Re) [s]; +infinity for basset or Re = 0.
  double crossover_time(double Re) const;
  /// K(s; Re), dimensionless; s > 0 [s].
  double K(double s, double Re) const;
  /// ∫_0^s K(σ; Re) dσ [s] (exact for basset: D√s/√(πν); a tabulated universal function otherwise).
  double integral(double s, double Re) const;

 private:
  KernelKind kind_;
  double D_, nu_, c1_ = 0, c2_ = 0;
};

/// s^(−1/2) ≈ Σ weight_i e^(−rate_i s) on [min_lag, horizon] (s in seconds).
struct SumOfExponentials {
  std::vector<double> rate;    // λ_i [1/s], ascending
  std::vector<double> weight;  // w_i [s^(−1/2)]
  double kappa = 0;            // short-lag correction 2√min_lag − Σ w_i (1 − e^(−λ_i min_lag))/λ_i [s^(1/2)]
  double min_lag = 0, horizon = 0;  // s
  double step = 0;             // trapezoid step h
  double max_rel_error = 0;    // measured max |SoE(s) √s − 1| on [min_lag, horizon] (dense log grid)
};
/// Nodes for a requested relative accuracy tol (h = π²/ln(7/tol)); throws std::invalid_argument
/// for min_lag ≤ 0, horizon ≤ min_lag, tol outside (1e-15, 0.1).
SumOfExponentials inverse_sqrt_soe(double min_lag, double horizon, double tol);
/// Nodes with exactly `modes` terms (the step h chosen for that count); modes in [2, 400].
SumOfExponentials inverse_sqrt_soe_modes(double min_lag, double horizon, int modes);

/// Transfer function of the history operator U ↦ ∫_0^t U' s^(−1/2): exact √π √(−iω), and the
/// sum-of-exponentials one (−iω)[Σ w_i/(λ_i − iω) + κ] (ω in rad/s, e^(−iωt) convention).
std::complex<double> inverse_sqrt_transfer(double omega);
std::complex<double> soe_transfer(const SumOfExponentials& soe, double omega);

/// A kernel in sum-of-exponentials form: fixed rates, weights and κ that depend smoothly on Re.
class SoeKernel {
 public:
  SoeKernel(const HistoryKernel& kernel, const SumOfExponentials& base);
  std::size_t modes() const { return rate_.size(); }
  const std::vector<double>& rates() const { return rate_; }  // 1/s
  /// K(s; Re) ≈ Σ w_i(Re) e^(−λ_i s) on [min_lag, horizon]; w dimensionless, κ(Re) [s].
  void weights(double Re, std::span<double> w, double& kappa) const;
  /// Measured max relative error of the fit against K on [min_lag, horizon] at this Re.
  double max_rel_error(double Re) const;
  const HistoryKernel& kernel() const { return kernel_; }
  const SumOfExponentials& base() const { return base_; }

 private:
  HistoryKernel kernel_;
  SumOfExponentials base_;
  std::vector<double> rate_;
  // Tabulated finite-Re weights (empty for basset): rows at ln s_c nodes.
  std::vector<double> ln_sc_;                 // ascending
  std::vector<std::vector<double>> w_table_;  // [node][mode]
  std::vector<std::vector<double>> dw_table_;  // dw/d ln s_c at the nodes (exact, for cubic Hermite)
  std::vector<double> w_basset_;
  std::vector<double> decay_;                 // (1 − e^(−λ_i min_lag))/λ_i, for κ(Re)
  double kappa_basset_ = 0;
  double tau0_ = 0, dtau_ = 0;                // uniform nodes ln_sc_[k] = tau0_ + k dtau_
};

/// Exact solutions of q' + αq + (γ/√π) d/dt ∫_0^t q(s)/√(t−s) ds = f (MODEL.md §2.3), α [1/s], γ [1/√s].
/// relaxation: f = 0, q(0) = 1; settling: f = 1, q(0) = 0.
double basset_relaxation(double alpha, double gamma, double t);
double basset_settling(double alpha, double gamma, double t);

}  // namespace imcol::contact
