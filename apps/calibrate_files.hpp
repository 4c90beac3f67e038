// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// imcol calibrate's files (docs/calibration.md): calibration.json, calibration.csv (every evaluation), measured.csv
// (the measurement, copied) and best.csv (the fitted run, or the table's rows with the fitted e).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "study/calibrate.hpp"

namespace imcol {

/// The evaluation cache's use (--cache): evaluations in the file at the start, taken from it, appended.
struct CacheUse {
  std::string path;
  std::size_t held = 0, reused = 0, added = 0;
};

/// Everything the files say: the calibration's inputs and its result, and the cache's use.
struct CalibrationRecord {
  const study::CalibrationInputs& in;
  const study::CalibrationResult& result;
  std::optional<CacheUse> cache;
};

/// calibration.json's content, all but its `run` block.
nlohmann::ordered_json calibration_json(const CalibrationRecord& rec);

/// Writes calibration.json (with `run`), calibration.csv, measured.csv and best.csv into `dir`.
void write_calibration_files(const std::filesystem::path& dir, const CalibrationRecord& rec, const nlohmann::ordered_json& run);

}  // namespace imcol
