// SPDX-License-Identifier: BSD-3-Clause
// The GMRES warm start by sub-cell offset (flow/solver.hpp, Settings::warm_start_by_offset): a sphere's ring forces
// follow its rings' offset on the grid, so the forces of its last steps in the same offset bin start the solve.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <vector>

#include "flow/solver.hpp"
#include "flow_settings.hpp"

namespace {

/// Two spheres approaching at a quarter cell a step each (the offsets repeat every four steps, one bin each at four
/// bins), from a gap of 1.4 D to 0.4 D: the forces of every step, the GMRES iterations and the applications of Q.
std::tuple<std::vector<double>, long, long> approach(bool by_offset) {
  // D = 1, Re = 1, fluid at rest; finest level r < 1.5 D, −0.5 D < z < 4.5 D at 8 cells/D
  auto st = imcol::flow::test_setup::stream_settings(1.0, 8, 2, 1.5, -0.5, 4.5, 0.01, 0.5);
  st.u_inf = 0.0;
  st.krylov_tol = 1e-8;
  st.preconditioner_bins = 4;
  st.warm_start_by_offset = by_offset;
  std::vector<imcol::flow::SphereState> sp{{0.5, 1.0, 0.0}, {0.5, 3.4, 0.0}};
  imcol::flow::Solver s(st, sp);
  std::vector<double> forces;
  long iterations = 0;
  for (int k = 1; k <= 16; ++k) {
    const double dz = 0.25 * st.h;
    sp[0] = {0.5, sp[0].z + dz, dz / st.dt};
    sp[1] = {0.5, sp[1].z - dz, -dz / st.dt};
    const auto info = s.step(sp);
    forces.insert(forces.end(), info.force.begin(), info.force.end());
    iterations += info.krylov_iterations;
  }
  return {forces, iterations, s.q_applications()};
}

}  // namespace

TEST(WarmStart, FromTheSameOffsetSavesIterationsAndChangesNoForce) {
  const auto [f_offset, it_offset, q_offset] = approach(true);
  const auto [f_last, it_last, q_last] = approach(false);
  // The same forces to the solve's tolerance: only where GMRES starts differs.
  ASSERT_EQ(f_offset.size(), f_last.size());
  for (std::size_t k = 0; k < f_last.size(); ++k) EXPECT_NEAR(f_offset[k], f_last[k], 1e-6 * std::abs(f_last[k])) << k;
  // Fewer iterations and applications of Q: the last two steps' forces are at other offsets (82 against 88
  // iterations; from the ninth step on, the third visit of each bin, the start is extrapolated in time).
  EXPECT_LT(it_offset, it_last);
  EXPECT_LT(q_offset, q_last);
}
