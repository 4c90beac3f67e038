// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The flow fields of every level at the vertices, computed once per snapshot and read by every writer (CSV:
// flow/snapshot.hpp, VTK: flow/vtk.hpp). Vertex k = i·(nz+1) + j at (r, z) = (i h, z0 + j h + z_shift), m.
// Fields (in this order: the CSV's columns after level,r,z): psi, the total Stokes streamfunction ψ + ½U∞r² (m³/s);
// omega, the azimuthal vorticity ω = η/r (1/s, 0 on the axis); u_r, u_z, the velocity (m/s) from ψ's face differences
// averaged to the vertices; p, the pressure p − p∞ (Pa; flow/pressure.hpp: the same in every frame, not physical
// inside the spheres). Velocities and ψ are seen from the frame given (SnapshotFrame).
#include <string>
#include <vector>

#include "flow/solver.hpp"

namespace imcol::flow {

/// Where the fields are seen from: the kernel's frame is at z_shift (m) and moves at u_frame (m/s) in the lab; t_shift (s)
/// is added to the kernel's time. The defaults write the kernel's own frame. `trajectory`: the spheres where the
/// collision model has them at the snapshot (lab z, m; lab u, m/s), drawn and blanked beside the kernel's
/// (flow/bodies.hpp); empty: where the kernel holds them.
struct SnapshotFrame {
  double z_shift = 0, u_frame = 0, t_shift = 0;
  std::vector<SphereState> trajectory;
};

/// One field at every vertex of a level.
struct PointField {
  std::string column;   // CSV column
  std::string name;     // VTK array name; for a vector's components, the vector's name
  int component = -1;   // -1: a scalar; 0, 1: the r and z component of the vector `name`
  std::vector<double> values;
};

struct LevelFields {
  LevelGeometry g;
  double z_shift = 0;              // added to g.z(j), m
  std::vector<PointField> fields;  // the CSV's column order
  double r(int i) const { return g.r(i); }
  double z(int j) const { return g.z(j) + z_shift; }
  /// The field whose CSV column is `column`, or null.
  const PointField* find(const std::string& column) const;
};

/// Every level's fields (level 0 the finest), seen from `frame`.
std::vector<LevelFields> level_fields(const Solver& s, const SnapshotFrame& frame = {});

}  // namespace imcol::flow
