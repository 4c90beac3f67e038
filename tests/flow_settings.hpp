// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Flow kernel settings for the coarse test runs: a sphere of D = 1 in a stream U = 1 along +z, ρ = 1, ν = 1/Re.
#include <cmath>

#include "flow/solver.hpp"

namespace imcol::flow::test_setup {

/// The finest level r < r_max, z_lo < z < z_hi at cpd cells per diameter; `levels` nested levels.
inline Settings stream_settings(double Re, int cpd, int levels, double r_max, double z_lo, double z_hi, double dt, double theta) {
  Settings s;
  s.nu = 1.0 / Re;
  s.density = 1.0;
  s.dt = dt;
  s.theta = theta;
  s.h = 1.0 / cpd;
  s.nr = static_cast<int>(std::lround(r_max * cpd));
  s.nz = static_cast<int>(std::lround((z_hi - z_lo) * cpd));
  s.levels = levels;
  s.z_center = 0.5 * (z_lo + z_hi);
  s.u_inf = 1.0;
  return s;
}

}  // namespace imcol::flow::test_setup
