// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The history memory's sum S(Δ) = Σ w_i z_i(t_n + Δ) [m/s] inside an accepted step of length h [s], for the outputs
// taken there (trajectory rows, the energy quadrature's middle), from values the step already has: S and S' at both
// ends (S'(0) the previous step's end slope) and S at one interior lag Δc, h/8 ≤ Δc ≤ 7h/8.
// The cubic Hermite H through the ends errs by e(s) = h⁴ S''''(ξ)/24 · B(s), B(s) = s²(1 − s)², s = Δ/h, largest at
// s = 1/2; its miss at Δc, d = S(Δc) − H(Δc), measures it: the largest error is about d B(1/2)/B(sc). The interpolant
// is H + d B(s)/B(sc), the quartic through all five values, used only where that estimate is within the tolerance;
// elsewhere the outputs are evaluated exactly.
namespace imcol::contact {

class StepOutputs {
 public:
  struct End {
    double value = 0, slope = 0;  // S [m/s], S' [m/s²]
  };
  static constexpr double kCheckFrom = 0.25;  // Δc/h within [kCheckFrom, 1 − kCheckFrom]

  /// The cubic's estimated largest error [m/s] on [0, h] from its miss at Δc (infinite for Δc outside the range).
  static double estimate(double h, End start, End end, double dc, double sc_value);
  /// Builds the interpolant on [0, h]; accepted when the estimate is within `tol` [m/s].
  StepOutputs(double h, End start, End end, double dc, double sc_value, double tol);
  bool accepted() const { return accepted_; }
  double error_estimate() const { return error_; }
  /// S(Δ), 0 ≤ Δ ≤ h.
  double value(double dt) const;

 private:
  static double bubble(double s) { return s * s * (1 - s) * (1 - s); }
  static double hermite(double h, End a, End b, double s);
  double h_;
  End a_, b_;
  double correction_ = 0;  // d / B(sc)
  double error_ = 0;
  bool accepted_ = false;
};

}  // namespace imcol::contact
