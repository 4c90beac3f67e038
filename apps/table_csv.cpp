// SPDX-License-Identifier: BSD-3-Clause
#include "apps/table_csv.hpp"

#include "apps/format.hpp"

namespace imcol {

std::string table_csv(const study::Table& t) {
  std::string out;
  for (std::size_t k = 0; k < t.columns.size(); ++k) out += (k ? "," : "") + t.columns[k].name;
  out += "\n";
  for (std::size_t i = 0; i < t.rows; ++i) {
    for (std::size_t k = 0; k < t.columns.size(); ++k) {
      const study::TableColumn& c = t.columns[k];
      if (k) out += ",";
      if (!c.words) {
        out += csv_number(c.numbers[i]);
        continue;
      }
      std::string w = c.text[i];
      for (char& ch : w)
        if (ch == ',' || ch == '\n') ch = ';';
      out += w;
    }
    out += "\n";
  }
  return out;
}

}  // namespace imcol
