// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Flow fields of every level as CSV (flow/fields.hpp): vertex rows "level,r,z,psi,omega,u_r,u_z,p" (m, m³/s, 1/s, m/s,
// Pa), level 0 the finest; ψ is the total Stokes streamfunction ψ + ½U∞r² seen from the lab, p is p − p∞. A comment
// line states the moment, the time,
// the shift added to z (coupled runs move the grid with the spheres), the spheres' lab positions where the kernel holds
// them, then where the trajectory has them and the true surface gap (flow/bodies.hpp):
// "...; spheres (z, d) = z1 d1 ...; trajectory spheres (z, d) = z1 d1 ...; gap = G m = G/D D".
#include <string>

#include <vector>

#include "flow/fields.hpp"
#include "flow/solver.hpp"

namespace imcol::flow {

/// label names the moment (it leads the picture's title). Velocities and ψ are written in the lab frame.
std::string snapshot_csv(const Solver& s, const SnapshotFrame& frame = {}, const std::string& label = "");
/// The same from fields already computed (level_fields(s, frame)): one column per field, in their order.
std::string snapshot_csv(const Solver& s, const std::vector<LevelFields>& levels, const SnapshotFrame& frame, const std::string& label);

}  // namespace imcol::flow
