// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol calibrate`: fit numeric scene keys to a measured trajectory or e table (docs/calibration.md). The search
// (calibrate/search.hpp) runs its evaluations on threads and, under mpirun, on every rank; rank 0 writes one
// output folder: calibration.json, calibration.csv, measured.csv, best.csv and calibration.png.
#include <optional>
#include <string>
#include <vector>

#include "calibrate/search.hpp"
#include "core/scene.hpp"

namespace imcol {

struct CalibrateOptions {
  std::string data;                  // --data: the measurement fitted to
  std::vector<std::string> fits;     // --fit KEY=LO:HI[:log], one per parameter
  std::string window;                // --window A:B: s around the measured contact; empty: the default window
  std::optional<double> offset_max;  // --offset-max T: s, bound on the fitted time offset
  calib::SearchOptions search;
  std::string validate;              // --validate: a measurement of the same kind, scored under the fitted values
  std::string cache;                 // --cache: a file of evaluations, taken from and added to (calibrate/evaluation_cache.hpp)
  int jobs = 0;                      // threads a rank; 0 = all cores
  std::string out;                   // default out/<scene name>-calibrate
  bool plot = true, progress = true;
};

/// Checks every input (scene, parameters, measurement, window, validation file, output folder) before anything runs,
/// then searches and writes the folder. Returns 0, or 3 if no evaluation succeeded.
int calibrate(const std::string& scene_path, const std::vector<Override>& overrides, const CalibrateOptions& opt);

}  // namespace imcol
