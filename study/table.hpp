// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A study's table: named columns of numbers (NaN where a row has none) or words, one entry per row. The command
// writes it as CSV, Python hands it out as NumPy arrays: the same cells.
#include <cstddef>
#include <deque>
#include <string>
#include <vector>

namespace imcol::study {

struct TableColumn {
  std::string name;
  bool words = false;                // words (text) rather than numbers
  std::vector<double> numbers;       // a numeric column: NaN = an empty cell
  std::vector<std::string> text;     // a word column
};

struct Table {
  std::deque<TableColumn> columns;  // a deque: add() keeps the columns added before where they are
  std::size_t rows = 0;
  /// Adds an empty column (numbers or words) and returns it.
  TableColumn& add(const std::string& name, bool words = false) {
    columns.push_back({name, words, {}, {}});
    return columns.back();
  }
};

}  // namespace imcol::study
