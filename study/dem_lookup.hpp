// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// e looked up in a restitution table (dem_table.csv) at a contact's St, as docs/dem.md (a) says: linear in ln St
// between rows; below the first row with e > 0, e = 0 (no rebound there); above the last row, the last row's e.
#include <vector>

namespace imcol::study {

struct RestitutionRow {
  double St = 0;  // > 0, rows sorted by St
  double e = 0;
};

/// e at St from the rows (sorted by St, at least one); throws std::invalid_argument on an empty table.
double lookup_restitution(const std::vector<RestitutionRow>& rows, double St);

}  // namespace imcol::study
