// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The GMRES preconditioner's sub-cell bins of a coupled run (flow/solver.hpp; flow.preconditioner_bins = 0, the
// default, chooses them). A moving sphere's block of Q is factorised at the first sub-cell offset it visits in each
// of b bins; at the block's own offset GMRES takes ~a iterations a step, at an offset up to 1/(2b) cell away
// ~a + c b^−0.6 (c ≈ 17–18 on gg3462 at 32 cells/D and gondret_st742 at 16, b = 1 … 64). Over S coupled steps (the
// developed start's steps at constant speed revisit the blocks' own offsets: gg3462's 64 take 258 applications of Q
// at 4, 8 and 16 bins alike, and the estimate charges them no extra iterations either) and M
// applications of Q per bin (each moving sphere's later block: flow/cost.hpp later_block_applications) the work
//   S (3 + a + c b^−0.6) + b M
// is least at b* = (0.6 c S / M)^(1/1.6), taken as the nearest power of two in [4, 64] (4: a prescribed start-up
// at constant speed visits 2–4 offsets per cell, each its own block).
namespace imcol::coupling {

/// Extra GMRES iterations a step at b bins are kGmresBinIterations × b^−0.6.
inline constexpr double kGmresBinIterations = 17.5;

/// b* above for `steps` coupled flow steps and `block_columns` applications of Q per bin (all moving
/// spheres' later blocks).
int automatic_bins(double steps, double block_columns);

/// The GMRES iterations a step at `bins` bins beyond those at the exact offset.
double bin_iterations(int bins);

}  // namespace imcol::coupling
