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
// a and c were measured at flow.krylov_tol = 1e-8; at another tolerance both scale with the decades the residual
// falls plus one, (1 + log10(1/tol)) / 9 (krylov_tolerance_factor): at 1e-4 the eight shipped coupled scenes with a
// collision take 0.60–0.80 (mean 0.72) of their iterations at 1e-6, the rule 5/7 = 0.71; at 1e-3 0.37–0.72 (0.56),
// the rule 0.57.
namespace imcol::coupling {

/// Extra GMRES iterations a step at b bins are kGmresBinIterations × b^−0.6 (at krylov_tol 1e-8).
inline constexpr double kGmresBinIterations = 17.5;

/// GMRES iterations at relative tolerance krylov_tol over those at 1e-8: (1 + log10(1/krylov_tol)) / 9.
double krylov_tolerance_factor(double krylov_tol);

/// b* above for `steps` coupled flow steps and `block_columns` applications of Q per bin (all moving
/// spheres' later blocks), with GMRES at relative tolerance krylov_tol.
int automatic_bins(double steps, double block_columns, double krylov_tol);

/// The GMRES iterations a step at `bins` bins beyond those at the exact offset, at relative tolerance krylov_tol.
double bin_iterations(int bins, double krylov_tol);

}  // namespace imcol::coupling
