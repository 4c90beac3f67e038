// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The folder of the shipped data (materials.csv, fluids.csv, scenes/, reference/, measurements/).
#include <string>

namespace imcol {

/// The data folder: $IMCOL_DATA_DIR if set and not empty, else the folder given to set_data_dir, else the source
/// tree's data/ (IMCOL_DATA_DIR at compile time).
std::string data_dir();

/// Sets the process's data folder (the installed Python package's imcol/data); "" clears it. Tables already read
/// (materials, fluids) keep what they read.
void set_data_dir(const std::string& dir);

}  // namespace imcol
