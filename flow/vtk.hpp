// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Flow fields as VTK XML files (ParaView, VisIt and meshio read them): per snapshot
//   STEM.vtm           a vtkMultiBlockDataSet: block "levels" (one dataset per level), block "bodies";
//   STEM_level<ℓ>.vtu  level ℓ whole (level 0 the finest) as an UnstructuredGrid of quads, points (x, y, z) = (r, z, 0) m;
//                      point data from flow/fields.hpp (velocity (u_r, u_z, 0) m/s, stream_function m³/s, vorticity
//                      1/s, and any field added there), cell data `level` and `finer` (1 where a finer level covers
//                      the cell: threshold finer < 0.5 to see each place once);
//   STEM_spheres.vtp   each sphere as a semicircle polyline in the (r, z) plane, cell data diameter (m), velocity (m/s);
//   STEM_wall.vtp      with a wall: the line z = z_w from the axis to the coarsest level's radius;
// and a time series (.pvd) over the snapshots' .vtm files. The .vtu arrays are appended raw binary (fields and points
// Float64, cells Int32, cell data UInt8; header_type UInt64; the machine's byte order); the bodies, a few hundred
// numbers, are ASCII with 17 digits.
#include <string>
#include <vector>

#include "flow/fields.hpp"
#include "flow/solver.hpp"

namespace imcol::flow {

struct NamedText {
  std::string name, content;
};

/// One snapshot's files; names are STEM… relative to the folder of STEM.vtm. `label` names the moment (an XML comment).
std::vector<NamedText> snapshot_vtk(const Solver& s, const std::vector<LevelFields>& levels, const SnapshotFrame& frame,
                                    const std::string& stem, const std::string& label);

/// One level as a .vtu file (see above).
std::string level_vtu(const std::vector<LevelFields>& levels, std::size_t level, const std::string& label);

struct SeriesEntry {
  double time = 0;    // s
  std::string file;   // relative to the .pvd's folder
  std::string label;
};
/// The .pvd time series (a ParaView Data collection); times must increase.
std::string vtk_series(const std::vector<SeriesEntry>& entries);

}  // namespace imcol::flow
