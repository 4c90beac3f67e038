// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A sweep's points: the values of one scene quantity (velocity, viscosity, diameter, density), the scene of each
// point, and one point's run (e and St, kinematics only).
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "run/run_summary.hpp"

namespace imcol::study {

/// The range of a sweep: `points` values of `vary` from `from` to `to` (SI units), log or linear spacing.
struct SweepRange {
  std::string vary;             // velocity | viscosity | diameter | density
  double from = 0, to = 0;
  int points = 0;
  std::string spacing = "log";  // log | linear
};

/// The values of the points: range.points from range.from to range.to, log or linear spacing.
std::vector<double> sweep_values(const SweepRange& range);

/// The quantities a sweep varies, in the order the help lists them.
std::vector<std::string> sweep_quantities();

/// The CSV column of a varied quantity ("velocity" → "velocity_m_s"); nullptr for an unknown one.
const char* sweep_column(const std::string& vary);

/// `vary` is one of sweep_quantities(); else InputError(where, key, naming the quantities).
void check_sweep_quantity(const std::string& vary, const std::string& where, const std::string& key);

/// Every value is a positive finite number and there are 1 to 100000; else InputError(where, key) naming the point.
void check_sweep_values(const std::string& vary, const std::vector<double>& values, const std::string& where, const std::string& key);

/// The scene keys one sweep point sets: `value` of the varied quantity on `base`.
std::vector<Override> sweep_overrides(const Scene& base, const std::string& vary, double value);

/// A scene read with the overrides given (a file's load_scene, or core/scene.hpp parse_scene of a text).
using SceneLoader = std::function<Scene(const std::vector<Override>&)>;

/// Every point's scene (the scene with `overrides`, then the point's sweep_overrides), built and validated before
/// anything runs: bad input stops the sweep at once (InputError naming the point). A viscosity sweep needs a [fluid].
std::vector<Scene> sweep_scenes(const SceneLoader& load, const std::vector<Override>& overrides, const Scene& base,
                                const std::string& vary, const std::vector<double>& values);
/// The same for a scene file.
std::vector<Scene> sweep_scenes(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                                const std::string& vary, const std::vector<double>& values);

/// One point of a sweep: what its run measured (ok), or why it failed (a solver failure ends this point only).
struct SweepPoint {
  bool ok = false;
  double value = NAN;   // of the varied quantity
  RunSummary summary;   // when ok
  std::string message;  // why e is missing, which measures disagree, the t_end it took; or the failure
};

/// Runs one point's scene (kinematics only; a point whose collision or rebound did not fit in solver.t_end is rerun
/// with t_end doubled, twice at most). Never throws for a failed run: ok is false then.
SweepPoint run_sweep_point(const Scene& scene, double value);

/// What became of e at a point that ran: measured, measures_disagree (the named measures differ from e by more
/// than measure.disagreement) or not_measured.
std::string e_status(const RunSummary& s);

/// "sweep point 3 (velocity = 0.5)": a point in messages.
std::string point_name(std::size_t i, const std::string& vary, double value);

}  // namespace imcol::study
