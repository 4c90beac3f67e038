// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One dimensionless Hertz impact with Tsuji et al.'s nonlinear damping (Tsuji, Tanaka & Ishida, Powder Technol. 71
// (1992) 239–250), the problem whose restitution sets the Hertz law's damping α (contact/hertz_law.hpp):
//   x'' = −max(0, x^{3/2} + α x^{1/4} x'),  x(0) = 0, x'(0) = 1   (x = ξ/L, L = (m* U²/k)^{2/5}, time in L/U).
// Classical RK4 at a fixed step h = 5e-5: e within 1e-9 of its converged value.
namespace imcol::contact {

/// Restitution, contact time (units L/U), peak overlap (units L).
struct TsujiImpact {
  double e = 1, t_contact = 0, x_max = 0;
};
TsujiImpact tsuji_impact(double alpha);

}  // namespace imcol::contact
