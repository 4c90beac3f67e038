// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Flow fields as VTK XML files (ParaView, VisIt and meshio read them); docs/coupling.md. Per snapshot:
//   STEM.vtm                  a vtkMultiBlockDataSet: block "levels" (one dataset per level), block "bodies";
//   STEM_level<ℓ>.vtu         level ℓ whole (0 the finest) as an UnstructuredGrid of quads in the plane y = 0: points
//                             (x, y, z) = (r, 0, z) m, the axis along z; point data from flow/fields.hpp, the unit in
//                             each name (velocity_m_s (u_r, 0, u_z), stream_function_m3_s, vorticity_1_s,
//                             pressure_Pa); cell data `level`, `finer` (1 where the next finer level covers the cell)
//                             and `vtkGhostType` (flow/hidden_cells.hpp: 32 = HIDDENCELL where a finer level covers the
//                             cell or its centre is inside a solid), so that a viewer shows each place once, in fluid;
//   STEM_spheres.vtp          the spheres where the trajectory (the collision model) has them: a semicircle polyline
//                             each in the same plane, cell data diameter_m, velocity_m_s;
//   STEM_kernel_spheres.vtp   the same where the flow kernel holds them (near contact short of the wall or each other);
//   STEM_wall.vtp             with a wall: the line z = z_w from the axis to the coarsest level's radius;
// every file's field data: time_s, and with a wall or a pair gap_m, gap_D (the trajectory's surface gap),
// kernel_gap_m, kernel_gap_D (the kernel's), D the first sphere's diameter. A time series (.pvd) over the .vtm files.
// The .vtu arrays are appended raw binary (fields and points Float64, cells Int32, cell data UInt8; header_type
// UInt64; the machine's byte order); the bodies and field data, a few hundred numbers, are ASCII with 17 digits.
#include <string>
#include <vector>

#include "flow/bodies.hpp"
#include "flow/fields.hpp"
#include "flow/solver.hpp"

namespace imcol::flow {

struct NamedText {
  std::string name, content;
};

/// One snapshot's files; names are STEM… relative to the folder of STEM.vtm. `label` names the moment (a comment).
std::vector<NamedText> snapshot_vtk(const Solver& s, const std::vector<LevelFields>& levels, const SnapshotFrame& frame,
                                    const std::string& stem, const std::string& label);

/// What every file of a snapshot states: its time (s), its label (a comment), its bodies.
struct SnapshotInfo {
  double time = 0;
  std::string label;
  const SnapshotBodies* bodies = nullptr;
};

/// One level as a .vtu file (see above).
std::string level_vtu(const std::vector<LevelFields>& levels, std::size_t level, const SnapshotInfo& in);

struct SeriesEntry {
  double time = 0;    // s
  std::string file;   // relative to the .pvd's folder
  std::string label;
};
/// The .pvd time series (a ParaView Data collection); times must increase.
std::string vtk_series(const std::vector<SeriesEntry>& entries);

}  // namespace imcol::flow
