// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A column of a study's table (its CSV file; the Python result's `table`): per row a number (NaN: missing), an
// integer or a word.
#include <functional>
#include <string>

namespace imcol::study {

template <class Row>
struct RowColumn {
  enum Kind { number, integer, word } kind;
  std::string name;
  std::function<double(const Row&)> value;      // number, integer
  std::function<std::string(const Row&)> text;  // word
};

}  // namespace imcol::study
