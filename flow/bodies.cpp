// SPDX-License-Identifier: BSD-3-Clause
#include "flow/bodies.hpp"

#include <cmath>
#include <limits>

namespace imcol::flow {

double SnapshotBodies::gap_of(const std::vector<SphereState>& set) const {
  if (set.size() == 2) return std::abs(set[1].z - set[0].z) - set[0].radius - set[1].radius;
  double g = std::numeric_limits<double>::infinity();
  if (wall_z)
    for (const auto& b : set) g = std::min(g, std::abs(*wall_z - b.z) - b.radius);
  return g;
}

bool SnapshotBodies::inside_solid(double r, double z) const {
  for (const auto* set : {&spheres, &kernel_spheres})
    for (const auto& b : *set)
      if (r * r + (z - b.z) * (z - b.z) < b.radius * b.radius) return true;
  if (!wall_z || spheres.empty()) return false;
  const double side = spheres.front().z >= *wall_z ? 1.0 : -1.0;  // the fluid's side of the wall
  return (z - *wall_z) * side < 0;
}

SnapshotBodies snapshot_bodies(const Solver& s, const SnapshotFrame& f) {
  SnapshotBodies b;
  for (const auto& k : s.spheres()) b.kernel_spheres.push_back({k.radius, k.z + f.z_shift, k.u + f.u_frame});
  b.spheres = f.trajectory.empty() ? b.kernel_spheres : f.trajectory;
  if (s.settings().wall_z) b.wall_z = *s.settings().wall_z + f.z_shift;
  return b;
}

}  // namespace imcol::flow
