// SPDX-License-Identifier: BSD-3-Clause
// The GMRES preconditioner's sub-cell bins (flow/solver.hpp): centred on the offset of the sphere's first block, so
// that an offset within half a bin of it reuses that block and one beyond gets its own.
#include <gtest/gtest.h>

#include "flow/solver.hpp"
#include "flow_settings.hpp"

namespace {

imcol::flow::Settings bins_test_settings() {
  // D = 1, Re = 1, fluid at rest; finest level r < 1.5 D, −0.5 D < z < 4.5 D at 8 cells/D (13 ring points a sphere)
  imcol::flow::Settings s = imcol::flow::test_setup::stream_settings(1.0, 8, 2, 1.5, -0.5, 4.5, 0.01, 0.5);
  s.u_inf = 0.0;
  s.krylov_tol = 1e-8;
  s.preconditioner_bins = 4;
  return s;
}

}  // namespace

TEST(FlowBins, BinsAreCentredOnTheFirstBlocksOffset) {
  const imcol::flow::Settings st = bins_test_settings();
  const double z_cell = -0.5 + 16 * st.h;  // a vertex line; offsets below are fractions of a cell past it
  auto at = [&](double offset, double z_before) {
    const double z = z_cell + offset * st.h;
    return imcol::flow::SphereState{0.5, z, (z - z_before) / st.dt};
  };
  imcol::flow::SphereState sp{0.5, z_cell, 0.0};
  imcol::flow::Solver s(st, {sp});
  for (double offset : {0.1, 0.2}) {  // the first block at 0.1; 0.2 is 0.4 of a bin from it
    sp = at(offset, sp.z);
    const auto info = s.step({sp});
    EXPECT_GT(info.krylov_iterations, 0);
  }
  EXPECT_EQ(s.preconditioner_blocks_built(), 1);  // bins at fixed offsets 0, ¼, ½, ¾ would have built two
  sp = at(0.4, sp.z);  // 1.2 bins from the first block: the next bin's own
  s.step({sp});
  EXPECT_EQ(s.preconditioner_blocks_built(), 2);
  sp = at(0.1 + 1.0, sp.z);  // a whole cell on from the first block: its bin again
  s.step({sp});
  EXPECT_EQ(s.preconditioner_blocks_built(), 2);
}
