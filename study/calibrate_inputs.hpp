// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A calibration's inputs (docs/calibration.md): the scene, the fitted keys and their start values, the measurement
// and its window, the held-out measurement; all read and checked before anything runs.
#include <optional>
#include <string>
#include <vector>

#include "calibrate/fit_parameter.hpp"
#include "calibrate/measurement.hpp"
#include "calibrate/objective.hpp"
#include "calibrate/search.hpp"
#include "core/scene.hpp"

namespace imcol::study {

/// What a calibration fits and how: the options of `imcol calibrate` that decide its result.
struct CalibrationOptions {
  std::string data;                  // the measurement fitted to (a trajectory or an e table, CSV)
  std::vector<std::string> fits;     // KEY=LO:HI[:log], one per parameter
  std::string window;                // A:B, s around the measured contact; empty: the default window
  std::optional<double> offset_max;  // s, bound on the fitted time offset
  calib::SearchOptions search;
  std::string validate;              // a measurement of the same kind, scored under the fitted values; empty: none
};

/// Where a parameter's search starts.
struct StartValue {
  double value = 0;             // within the bounds
  std::optional<double> scene;  // the scene's own value, if it has one
  std::string from;             // how `value` was chosen
};

/// Every input, read and checked.
struct CalibrationInputs {
  std::string scene_path;
  std::vector<Override> overrides;
  Scene base;
  std::vector<calib::FitParameter> params;
  std::vector<StartValue> start;
  std::string data_path;
  std::string data_text;  // the measurement file's text, as read once
  calib::Measurement data;
  std::optional<calib::TrajectoryWindow> window;  // a trajectory's
  std::string held_out_path;
  std::optional<calib::Measurement> held_out;
  std::optional<calib::TrajectoryWindow> held_window;
  calib::SearchOptions search;  // as given, inner_parameters set (a trajectory's time offset)
  bool trajectory() const;
};

/// "a trajectory" or "an e table".
const char* kind_of(const calib::Measurement& m);

/// Reads and checks every input (scene, parameters, measurement, window, validation file); InputError naming the
/// option (as the command line spells it) or the file and line.
CalibrationInputs read_calibration_inputs(const std::string& scene_path, const std::vector<Override>& overrides,
                                          const CalibrationOptions& opt);

}  // namespace imcol::study
