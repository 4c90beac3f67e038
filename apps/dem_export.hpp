// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol sweep … --export dem`: e against St in the shape a soft-sphere DEM code reads (docs/dem.md).
//   dem.csv        one row per sweep point: the varied value, impact speed, St, e, e/e_dry, status (failed points too)
//   dem_table.csv  St, e, e/e_dry of the points with e, sorted by St: a restitution table to look up
//   dem.json       the fits of e = e_dry f(St_c/St) (study/dem_fit.hpp), exp and linear, e_dry fixed and free
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "study/dem_fit.hpp"

namespace imcol {

using study::DemPoint;

/// What the sweep varied and where its table says so.
struct DemSweep {
  std::string scene_file, vary, column;  // column: e.g. velocity_m_s
  std::optional<double> e_dry;           // the scene's dry restitution (none without a contact)
};

/// Writes dem.csv, dem_table.csv and dem.json into `dir`; returns the terminal's line (St_c, e_dry, residual, range).
std::string export_dem(const std::filesystem::path& dir, const Scene& base, const DemSweep& sweep, const std::vector<DemPoint>& pts);

}  // namespace imcol
