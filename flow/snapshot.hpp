// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Flow fields of every level as CSV: vertex rows "level,r,z,psi,omega,u_r,u_z,p" (m, m³/s, 1/s, m/s, Pa), level 0 the
// finest; ψ is the total Stokes streamfunction ψ + ½U∞r² seen from the lab; p is p − p∞ (flow/pressure.hpp: the same
// in every frame; not physical inside the spheres). A comment line states the moment, the time,
// the shift added to z (coupled runs move the grid with the spheres) and the spheres' lab positions.
#include <string>

#include "flow/solver.hpp"

namespace imcol::flow {

/// Where the fields are seen from: the kernel's frame is at z_shift (m) and moves at u_frame (m/s) in the lab; t_shift (s)
/// is added to the kernel's time. The defaults write the kernel's own frame.
struct SnapshotFrame {
  double z_shift = 0, u_frame = 0, t_shift = 0;
};

/// label names the moment (it leads the picture's title). Velocities and ψ are written in the lab frame.
std::string snapshot_csv(const Solver& s, const SnapshotFrame& frame = {}, const std::string& label = "");

}  // namespace imcol::flow
