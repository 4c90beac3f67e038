// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// imcol calibrate's files (docs/calibration.md): calibration.json, calibration.csv (every evaluation), measured.csv
// (the measurement, copied) and best.csv (the fitted run, or the table's rows with the fitted e).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/calibrate_progress.hpp"
#include "calibrate/fit_parameter.hpp"
#include "calibrate/measurement.hpp"
#include "calibrate/objective.hpp"
#include "calibrate/search.hpp"
#include "core/scene.hpp"
#include "run/simulate.hpp"

namespace imcol {

/// Where a parameter's search starts.
struct StartValue {
  double value = 0;             // within the bounds
  std::optional<double> scene;  // the scene's own value, if it has one
  std::string from;             // how `value` was chosen
};

/// The hold-out (--validate) scored under the fitted values.
struct Validation {
  calib::Evaluation eval;
};

/// Everything the files say.
struct CalibrationRecord {
  std::string scene_path;
  std::vector<Override> overrides;
  Scene base;
  std::vector<calib::FitParameter> params;
  std::vector<StartValue> start;
  calib::Measurement data;
  std::string data_text;  // the measurement file's text (measured.csv)
  std::optional<calib::TrajectoryWindow> window;
  std::optional<calib::Measurement> held_out;
  std::optional<calib::TrajectoryWindow> held_window;
  calib::SearchOptions search;
  calib::SearchResult result;
  const Validation* validation = nullptr;
  const RunResult* best_run = nullptr;  // a trajectory's fitted run
  std::string best_run_error;           // why it is missing
  double wall_s = 0;
  int jobs = 1, ranks = 1;
  StageTimes stage_times;
  struct Cache {
    std::string path;
    std::size_t held = 0, reused = 0, added = 0;  // evaluations in the file at the start, taken from it, appended
  };
  std::optional<Cache> cache;  // --cache
};

/// The evaluations in an order that does not depend on where or when they ran: by stage, then work item, each item's
/// own in the order it made them.
void sort_evaluations(calib::SearchResult& r);

/// calibration.json's content, all but its `run` block.
nlohmann::ordered_json calibration_json(const CalibrationRecord& rec);

/// Writes calibration.json (with `run`), calibration.csv, measured.csv and best.csv into `dir`.
void write_calibration_files(const std::filesystem::path& dir, const CalibrationRecord& rec, const nlohmann::ordered_json& run);

}  // namespace imcol
