// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol sweep … --export dem`: e against St in the shape a soft-sphere DEM code reads (docs/dem.md).
//   dem.csv        one row per sweep point: the varied value, impact speed, St, e, e/e_dry, status (failed points too)
//   dem_table.csv  St, e, e/e_dry of the points with e, sorted by St: a restitution table to look up
//   dem.json       the fits of e = e_dry f(St_c/St) (run/restitution_fit.hpp), exp and linear, e_dry fixed and free
// St is m* U / (6 π μ a*²) (the convention of LIGGGHTS's viscous restitution): the summary's St for a wall,
// St_B_eq_6_2 for a pair (twice the summary's St there).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace imcol {

/// One sweep point as the export reads it.
struct DemPoint {
  double value = 0;  // of the varied quantity, SI
  bool ok = false;   // the run finished (sweep.csv status ok)
  std::string e_status;  // measured | measures_disagree | not_measured (empty for a failed run)
  std::optional<double> impact_speed_m_s, St, St_B_eq_6_2, e;
};

/// What the sweep varied and where its table says so.
struct DemSweep {
  std::string scene_file, vary, column;  // column: e.g. velocity_m_s
  std::optional<double> e_dry;           // the scene's dry restitution (none without a contact)
};

/// The largest |residual| in e a fit may have to be said to fit the data (dem.json `supported`).
inline constexpr double kDemFitTolerance = 0.05;

/// Writes dem.csv, dem_table.csv and dem.json into `dir`; returns the terminal's line (St_c, e_dry, residual, range).
std::string export_dem(const std::filesystem::path& dir, const Scene& base, const DemSweep& sweep, const std::vector<DemPoint>& pts);

}  // namespace imcol
