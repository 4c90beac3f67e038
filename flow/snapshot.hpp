#pragma once
// Flow fields of every level as CSV: vertex rows "level,r,z,psi,omega,u_r,u_z" (m, m³/s, 1/s, m/s), level 0 the
// finest; ψ is the total Stokes streamfunction ψ + ½U∞r². A comment line states the time, the shift added to z
// (the frame's position: coupled runs move the grid with the spheres) and the spheres' lab positions.
#include <string>

#include "flow/solver.hpp"

namespace imcol::flow {

/// z_shift (m) is added to every z (frame origin in the lab); label names the moment (for the picture's title).
std::string snapshot_csv(const Solver& s, double z_shift = 0.0, const std::string& label = "");

}  // namespace imcol::flow
