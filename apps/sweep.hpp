// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol sweep`: e against St over a range of one scene quantity, the points run in parallel (the engine:
// study/sweep.hpp).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.hpp"
#include "study/sweep.hpp"
#include "study/sweep_columns.hpp"

namespace imcol {

using study::check_sweep_quantity;
using study::check_sweep_values;
using study::run_sweep_point;
using study::sweep_column;
using study::sweep_columns;
using study::sweep_overrides;
using study::sweep_quantities;
using study::sweep_scenes;
using study::sweep_values;
using study::SweepColumn;
using study::SweepPoint;

/// The range (vary, from, to, points, spacing) and how the command runs and writes it.
struct SweepOptions : study::SweepRange {
  int jobs = 0;              // 0 = all cores
  std::string out;           // default out/<scene>-sweep_<vary>
  bool progress = true;      // on a terminal only
  bool plot = true;
  std::string export_format;  // "dem": dem.csv, dem_table.csv, dem.json (apps/dem_export.hpp); empty: none
};

/// The scene a command's json describes: scene (name), scene_file, overrides (as given), configuration.
nlohmann::ordered_json scene_json(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base);

/// A sweep's settings into j: vary, column (the CSV column of the varied quantity), from, to, points, spacing.
void put_sweep_settings(nlohmann::ordered_json& j, const study::SweepRange& opt, const char* column);

/// Runs the sweep; rewrites DIR/sweep.csv as points finish (at most every 0.25 s, and at the end), so
/// that finished points survive a later failure or an interrupt; then DIR/sweep.json, the export's files and DIR/sweep.png.
/// Returns 0, or 3 if any point failed.
int sweep(const std::string& scene_path, const std::vector<Override>& overrides, const SweepOptions& opt);

}  // namespace imcol
