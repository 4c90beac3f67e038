// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A study's table (study/table.hpp) as CSV: a header of the column names, numbers with 12 significant digits (an
// empty cell for NaN), words with their commas and line breaks turned to ';'.
#include <string>

#include "study/table.hpp"

namespace imcol {

std::string table_csv(const study::Table& t);

}  // namespace imcol
