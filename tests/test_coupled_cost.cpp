// SPDX-License-Identifier: BSD-3-Clause
// The coupled run's cost pieces: FFT-friendly axial cell counts (flow/fft_size.hpp), the preconditioner bins chosen
// from the run's steps (coupling/preconditioner_bins.hpp) and the estimate's parts (coupling/run_cost.hpp).
#include <gtest/gtest.h>

#include "coupling/preconditioner_bins.hpp"
#include "coupling/run_cost.hpp"
#include "flow/fft_size.hpp"

namespace {

imcol::coupling::CoupledCostInput coupled_cost_pair_input() {
  imcol::coupling::CoupledCostInput in;
  in.settings.h = 0.0127 / 32;
  in.settings.nr = 32;
  in.settings.nz = 180;
  in.settings.levels = 4;
  in.settings.preconditioner_bins = 4;
  in.diameters = {0.0127, 0.0127};
  in.start_up_steps = 64;
  in.steps = 28;
  in.snapshots = 4;
  in.start_up_travel = {0.5 * 0.0127, 0.5 * 0.0127};
  in.moves_after = {true, true};
  return in;
}

}  // namespace

TEST(CoupledCost, AxialCellsAreSevenSmoothMultiplesOfFour) {
  EXPECT_EQ(imcol::flow::fft_friendly_cells(116, 4), 120);  // 4 · 29 → 2³ · 3 · 5
  EXPECT_EQ(imcol::flow::fft_friendly_cells(92, 4), 96);    // 4 · 23
  EXPECT_EQ(imcol::flow::fft_friendly_cells(180, 4), 180);  // already 2² · 3² · 5
  EXPECT_EQ(imcol::flow::fft_friendly_cells(208, 4), 216);  // 2⁴ · 13 → 2³ · 3³
  EXPECT_EQ(imcol::flow::fft_friendly_cells(1, 4), 4);
}

TEST(CoupledCost, BinsGrowWithTheStepsAndStayInRange) {
  using imcol::coupling::automatic_bins;
  EXPECT_EQ(automatic_bins(92, 204), 4);     // gg3462: 92 steps, two spheres of 51 ring points
  EXPECT_EQ(automatic_bins(28, 48), 4);      // gg3462 probed: 28 coupled steps, two later blocks of 24 applications
  EXPECT_EQ(automatic_bins(9000, 52), 64);   // gondret_st742: ~9 000 steps, one sphere of 26
  EXPECT_EQ(automatic_bins(600, 52), 16);    // gondret_st27
  EXPECT_EQ(automatic_bins(1e9, 1), 64);
  EXPECT_EQ(automatic_bins(0, 52), 4);
  EXPECT_GT(imcol::coupling::bin_iterations(4), imcol::coupling::bin_iterations(64));
}

TEST(CoupledCost, TheTotalIsItsPartsAndEachPartGrowsWithItsCount) {
  auto in = coupled_cost_pair_input();
  const auto c = imcol::coupling::coupled_cost(in);
  EXPECT_GT(c.start_up_s, 0);
  EXPECT_GT(c.blocks_s, 0);
  EXPECT_GT(c.steps_s, 0);
  EXPECT_GT(c.fields_s, 0);
  EXPECT_DOUBLE_EQ(c.total_s(), c.start_up_s + c.blocks_s + c.steps_s + c.fields_s);
  in.steps *= 2;
  in.snapshots = 0;
  const auto d = imcol::coupling::coupled_cost(in);
  EXPECT_DOUBLE_EQ(d.steps_s, 2 * c.steps_s);
  EXPECT_EQ(d.fields_s, 0);
  EXPECT_DOUBLE_EQ(d.blocks_s, c.blocks_s);
  // More bins: more blocks, fewer GMRES iterations a step.
  in.settings.preconditioner_bins = 64;
  const auto e = imcol::coupling::coupled_cost(in);
  EXPECT_GT(e.blocks_s, d.blocks_s);
  EXPECT_LT(e.steps_s, d.steps_s);
}
