#pragma once
// What a flow run will cost, estimated from its grid before anything is allocated (measured constants:
// docs/flow-kernel.md "cost"): memory ~100 bytes per vertex and level plus the force system's dense matrices
// (Q of the body points, its LU, and up to 16 cached preconditioner blocks per moving sphere); time ~50 ns per
// vertex, level and step, twice that with moving bodies (GMRES on the force system).
#include <span>
#include <string>

#include "flow/solver.hpp"

namespace imcol::flow {

struct CostEstimate {
  double vertices = 0;          // all levels
  double body_points = 0;       // rings of the spheres and the wall
  double bytes = 0;             // peak memory of the solver, B
  double seconds_per_step = 0;  // s
};

/// `diameters`: the spheres' (m); `moving`: bodies move relative to the grid.
CostEstimate estimate_cost(const Settings& s, std::span<const double> diameters, bool moving);

/// This machine's physical memory, B (0 if unknown).
double physical_memory_bytes();

/// Empty if the estimate fits in half of this machine's memory; otherwise why not ("needs about … GB (…
/// vertices, … body points), more than half of this machine's … GB"), for the caller's error message.
std::string memory_refusal(const CostEstimate& c);

}  // namespace imcol::flow
