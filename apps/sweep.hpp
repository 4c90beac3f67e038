// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol sweep`: e against St over a range of one scene quantity, the points run in parallel.
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.hpp"
#include "run/run_summary.hpp"

namespace imcol {

struct SweepOptions {
  std::string vary;          // velocity | viscosity | diameter | density
  double from = 0, to = 0;   // SI units of the varied quantity
  int points = 0;
  std::string spacing = "log";  // log | linear
  int jobs = 0;              // 0 = all cores
  std::string out;           // default out/<scene>-sweep_<vary>
  bool progress = true;      // on a terminal only
  bool plot = true;
  std::string export_format;  // "dem": dem.csv, dem_table.csv, dem.json (apps/dem_export.hpp); empty: none
};

/// The quantities a sweep varies (--vary), in the order the help lists them.
std::vector<std::string> sweep_quantities();

/// `vary` is one of sweep_quantities(); else InputError(where, key, the --vary option's message).
void check_sweep_quantity(const std::string& vary, const std::string& where, const std::string& key);

/// Every value is a positive finite number and there are 1 to 100000; else InputError(where, key) naming the point.
void check_sweep_values(const std::string& vary, const std::vector<double>& values, const std::string& where, const std::string& key);

/// The scene keys one sweep point sets (exposed for tests): `value` of the varied quantity on `base`.
std::vector<Override> sweep_overrides(const Scene& base, const std::string& vary, double value);

/// Every point's scene (the scene with `overrides`, then the point's sweep_overrides), built and validated before
/// anything runs: bad input stops the sweep at once (InputError naming the point).
/// A viscosity sweep needs a [fluid] table (InputError naming the scene file).
std::vector<Scene> sweep_scenes(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                                const std::string& vary, const std::vector<double>& values);
/// The same for a scene that is not a file: `load` reads it with the overrides given (core/scene.hpp parse_scene).
std::vector<Scene> sweep_scenes(const std::function<Scene(const std::vector<Override>&)>& load, const std::vector<Override>& overrides,
                                const Scene& base, const std::string& vary, const std::vector<double>& values);

/// One point of a sweep: what its run measured (ok), or why it failed (a solver failure ends this point only).
struct SweepPoint {
  bool ok = false;
  double value = NAN;   // of the varied quantity
  RunSummary summary;   // when ok
  std::string message;  // why e is missing, which measures disagree, the t_end it took; or the failure
};

/// Runs one point's scene as imcol sweep does (kinematics only; a point whose collision or rebound did not fit in
/// solver.t_end is rerun with t_end doubled, twice at most). Never throws for a failed run: ok is false then.
SweepPoint run_sweep_point(const Scene& scene, double value);

/// sweep.csv's columns after `point` and the varied quantity's, in the file's order: a number (missing: an empty
/// cell) or a word per point.
struct SweepColumn {
  const char* name;
  std::optional<double> (*number)(const SweepPoint&);  // a numeric column; null for a word column
  std::string (*word)(const SweepPoint&);              // a word column (status, message, e_is, e_status)
};
const std::vector<SweepColumn>& sweep_columns();

/// The CSV column of a varied quantity ("velocity" → "velocity_m_s"); nullptr for an unknown one.
const char* sweep_column(const std::string& vary);

/// The scene a command's json describes: scene (name), scene_file, overrides (as given), configuration.
nlohmann::ordered_json scene_json(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base);

/// A sweep's settings into j: vary, column (the CSV column of the varied quantity), from, to, points, spacing.
void put_sweep_settings(nlohmann::ordered_json& j, const SweepOptions& opt, const char* column);

/// The values of the points: opt.points from opt.from to opt.to, log or linear spacing (opt.spacing).
std::vector<double> sweep_values(const SweepOptions& opt);

/// Runs the sweep; rewrites DIR/sweep.csv as points finish (at most every 0.25 s, and at the end), so
/// that finished points survive a later failure or an interrupt; then DIR/sweep.json, the export's files and DIR/sweep.png.
/// Returns 0, or 3 if any point failed.
int sweep(const std::string& scene_path, const std::vector<Override>& overrides, const SweepOptions& opt);

}  // namespace imcol
