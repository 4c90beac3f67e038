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
  constexpr double tol = 1e-8;  // the tolerance the iteration constants were measured at
  EXPECT_EQ(automatic_bins(92, 204, tol), 4);     // gg3462: 92 steps, two spheres of 51 ring points
  EXPECT_EQ(automatic_bins(28, 48, tol), 4);      // gg3462 probed: 28 coupled steps, two later blocks of 24 applications
  EXPECT_EQ(automatic_bins(9000, 52, tol), 64);   // gondret_st742: ~9 000 steps, one sphere of 26
  EXPECT_EQ(automatic_bins(600, 52, tol), 16);    // gondret_st27
  EXPECT_EQ(automatic_bins(1e9, 1, tol), 64);
  EXPECT_EQ(automatic_bins(0, 52, tol), 4);
  EXPECT_GT(imcol::coupling::bin_iterations(4, tol), imcol::coupling::bin_iterations(64, tol));
  // At the default 1e-4 these counts give the same bins: fewer iterations per bin, but the powers of two round alike.
  EXPECT_EQ(automatic_bins(9000, 52, 1e-4), 64);
  EXPECT_EQ(automatic_bins(600, 52, 1e-4), 16);
  EXPECT_EQ(automatic_bins(28, 48, 1e-4), 4);
}

TEST(CoupledCost, IterationsScaleWithTheDecadesTheResidualFalls) {
  using imcol::coupling::krylov_tolerance_factor;
  EXPECT_DOUBLE_EQ(krylov_tolerance_factor(1e-8), 1.0);
  EXPECT_NEAR(krylov_tolerance_factor(1e-4) / krylov_tolerance_factor(1e-6), 5.0 / 7.0, 1e-12);
  EXPECT_NEAR(krylov_tolerance_factor(1e-3) / krylov_tolerance_factor(1e-6), 4.0 / 7.0, 1e-12);
  EXPECT_DOUBLE_EQ(krylov_tolerance_factor(1.0), 1.0 / 9.0);  // one iteration's worth, never less
  EXPECT_NEAR(imcol::coupling::bin_iterations(4, 1e-4) / imcol::coupling::bin_iterations(4, 1e-8), 5.0 / 9.0, 1e-12);
  // The estimate's steps shrink with the tolerance, the rest of it does not.
  auto in = coupled_cost_pair_input();
  in.settings.krylov_tol = 1e-8;
  const auto tight = imcol::coupling::coupled_cost(in);
  in.settings.krylov_tol = 1e-4;
  const auto loose = imcol::coupling::coupled_cost(in);
  EXPECT_LT(loose.steps_s, tight.steps_s);
  EXPECT_LT(loose.start_up_s, tight.start_up_s);
  EXPECT_DOUBLE_EQ(loose.blocks_s, tight.blocks_s);
  EXPECT_DOUBLE_EQ(loose.fields_s, tight.fields_s);
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
