// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// sweep.csv's columns after `point` and the varied quantity's, in the file's order: what the command's file and
// Python's SweepResult both read from a point.
#include <optional>
#include <string>
#include <vector>

#include "study/sweep_points.hpp"

namespace imcol::study {

/// A number (missing: an empty cell) or a word per point.
struct SweepColumn {
  const char* name;
  std::optional<double> (*number)(const SweepPoint&);  // a numeric column; null for a word column
  std::string (*word)(const SweepPoint&);              // a word column (status, message, e_is, e_status)
};
const std::vector<SweepColumn>& sweep_columns();

}  // namespace imcol::study
