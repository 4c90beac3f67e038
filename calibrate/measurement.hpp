// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Measurements `imcol calibrate` fits to, read from CSV (header line, then one row per sample; '#' lines are comments):
//  * a trajectory: columns `t` (s) and `z1` and/or `z2` (m), the names of imcol's trajectory.csv; times strictly
//    increasing; at least kMinTrajectoryRows rows;
//  * an e table: one or more numeric scene keys as --set takes them (e.g. `sphere[0].velocity`) and `e`; each row
//    is one run of the scene with those keys set; at least kMinTableRows rows.
// The kind is told by the header: `t` first → trajectory; an `e` column → table.
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace imcol::calib {

inline constexpr std::size_t kMinTrajectoryRows = 5, kMinTableRows = 2;
/// The largest measurement file read (64 MiB: about a million rows of a trajectory with two columns).
inline constexpr std::uintmax_t kMaxMeasurementBytes = std::uintmax_t{64} << 20;

struct MeasuredTrajectory {
  std::string path;
  std::vector<double> t;                  // s, strictly increasing
  std::vector<std::string> columns;       // "z1", "z2" (those present, in file order)
  std::vector<std::vector<double>> z;     // z[c][k]: column c at t[k], m
  std::vector<int> lines;                 // the file line of each row
  int header_line = 0;                    // the file line of the header
};

struct MeasuredTable {
  std::string path;
  std::vector<std::string> keys;          // scene keys, file order
  std::vector<std::vector<double>> values;  // values[r][k]: row r's value of keys[k]
  std::vector<double> e;                  // measured e of each row, in [0, 1]
  std::vector<int> lines;                 // the file line of each row
};

using Measurement = std::variant<MeasuredTrajectory, MeasuredTable>;

/// Reads a measurement file: a regular file of at most kMaxMeasurementBytes (core/text_file.hpp), then
/// parse_measurement. Bad input (a missing file, a directory, a device or FIFO, a larger file) throws InputError(path).
Measurement read_measurement(const std::string& path);

/// Reads the measurement `text` of file `path`; a leading UTF-8 byte order mark is skipped. Bad input (an unknown
/// column, a cell that is not a finite number or lies outside 0 and [1e-30, 1e30] in magnitude, times not strictly
/// increasing, too few rows, e outside [0, 1]) throws InputError(path:line, column, problem).
Measurement parse_measurement(const std::string& path, const std::string& text);

}  // namespace imcol::calib
