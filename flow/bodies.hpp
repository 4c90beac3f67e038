// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The solids a flow-field snapshot shows, in the lab (m, m/s): the spheres where the trajectory has them (the
// collision model's state at the snapshot), the spheres where the flow kernel holds them (near contact the kernel
// keeps its gap at flow.min_gap_cells·h or more: docs/coupling.md), the wall, and the true surface gap
// (sphere–wall: the nearest sphere's surface to the wall; pair: surface to surface).
// A point (r, z) is inside a solid when it is strictly inside either sphere of either set, or strictly beyond the
// wall (on the side away from the trajectory's first sphere).
#include <optional>
#include <vector>

#include "flow/fields.hpp"
#include "flow/solver.hpp"

namespace imcol::flow {

struct SnapshotBodies {
  std::vector<SphereState> spheres;         // the trajectory's (lab z and u)
  std::vector<SphereState> kernel_spheres;  // where the kernel holds them (lab z and u)
  std::optional<double> wall_z;             // lab, m
  /// Surface gap of `set` (spheres or kernel_spheres), m; +∞ with one sphere and no wall.
  double gap_of(const std::vector<SphereState>& set) const;
  double gap() const { return gap_of(spheres); }
  double kernel_gap() const { return gap_of(kernel_spheres); }
  double diameter() const { return 2 * spheres.front().radius; }  // D, the first sphere's, m
  bool inside_solid(double r, double z) const;
};

/// The snapshot's bodies: the kernel's spheres and wall seen from `frame` (lab), the trajectory's from
/// frame.trajectory (the kernel's when that is empty: prescribed motion, `imcol flow`).
SnapshotBodies snapshot_bodies(const Solver& s, const SnapshotFrame& frame);

}  // namespace imcol::flow
