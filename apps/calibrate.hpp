// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol calibrate`: fit numeric scene keys to a measured trajectory or e table (docs/calibration.md). The
// calibration (study/calibrate.hpp) runs its evaluations on threads and, under mpirun, on every rank; rank 0 prints
// its result and writes one output folder: calibration.json, calibration.csv, measured.csv, best.csv and
// calibration.png.
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "study/calibrate_inputs.hpp"

namespace imcol {

/// The calibration's options (--data, --fit, --window, --offset-max, the search's, --validate) and the command's.
struct CalibrateOptions : study::CalibrationOptions {
  std::string cache;  // --cache: a file of evaluations, taken from and added to (calibrate/evaluation_cache.hpp)
  int jobs = 0;       // threads a rank; 0 = all cores
  std::string out;    // default out/<scene name>-calibrate
  bool plot = true, progress = true;
};

/// Checks every input (scene, parameters, measurement, window, validation file, cache, output folder) before anything
/// runs, then calibrates and writes the folder. Returns 0, or 3 if no evaluation succeeded.
int calibrate(const std::string& scene_path, const std::vector<Override>& overrides, const CalibrateOptions& opt);

}  // namespace imcol
