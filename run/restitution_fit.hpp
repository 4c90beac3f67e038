// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A fit of the restitution coefficient against the Stokes number, e(St) = e_dry f(St_c / St), the forms soft-sphere
// DEM codes take (docs/dem.md):
//   exponential: f = exp(−St_c/St)          (Legendre, Zenit, Daniel & Guiraud 2006; Izard, Bonometti & Lacaze 2014)
//   linear:      f = max(0, 1 − St_c/St)    (e reaches 0 at St = St_c)
// Least squares in e (Eigen's Levenberg–Marquardt), started from the linearised fit (ln e, or e, linear in 1/St).
// Only samples with e > 0 enter: e = 0 (no rebound) is the limit the forms approach but do not fit, and a sample
// without e (a failed run, e not measured) has nothing to fit; both are counted. St in any one convention: St_c comes
// out in the same one.
#include <cstddef>
#include <optional>
#include <vector>

namespace imcol::run {

enum class RestitutionForm { exponential, linear };
/// "exp" | "linear" (dem.json `form`).
const char* to_string(RestitutionForm f);
/// The form as a formula, e.g. "e = e_dry exp(-St_c/St)".
const char* formula(RestitutionForm f);

/// e_dry f(St_c / St) (0 for St <= 0).
double restitution_model(RestitutionForm form, double St_c, double e_dry, double St);

struct RestitutionSample {
  double St = 0;            // > 0 where e is given
  std::optional<double> e;  // none: the run failed or e was not measured
};

struct RestitutionFit {
  RestitutionForm form = RestitutionForm::exponential;
  bool e_dry_free = false;
  double St_c = 0, e_dry = 0;
  double St_c_std_error = 0, e_dry_std_error = 0;  // from s² (JᵀJ)⁻¹, s² = Σr²/(n − p); 0 for a fixed e_dry
  double rms_residual = 0, max_residual = 0;       // in e, over the samples used
  std::size_t used = 0, no_rebound = 0, without_e = 0;  // samples with e > 0, e = 0, no e
  double St_min = 0, St_max = 0;                   // the samples used: the fit's range of validity
  std::optional<double> St_no_rebound_max;         // the largest St with e = 0
  int iterations = 0;                              // Levenberg–Marquardt
};

/// The fewest samples with e > 0 a fit takes: 2 with e_dry fixed, 3 with e_dry free (one more than its parameters).
std::size_t min_restitution_samples(bool e_dry_free);

/// Fits `form` to `samples`, e_dry fixed to `e_dry` or, without it, a parameter. Throws std::invalid_argument when
/// fewer than min_restitution_samples() samples have e > 0 (the message counts them), when a sample with e has
/// St <= 0 or a non-finite St or e, or when a fixed e_dry is not in (0, 1].
RestitutionFit fit_restitution(const std::vector<RestitutionSample>& samples, RestitutionForm form,
                               std::optional<double> e_dry = std::nullopt);

}  // namespace imcol::run
