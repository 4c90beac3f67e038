// SPDX-License-Identifier: BSD-3-Clause
#include "study/dem_lookup.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace imcol::study {

double lookup_restitution(const std::vector<RestitutionRow>& rows, double St) {
  if (rows.empty()) throw std::invalid_argument("lookup_restitution: an empty table");
  const auto first = std::find_if(rows.begin(), rows.end(), [](const RestitutionRow& r) { return r.e > 0; });
  if (first == rows.end() || St < first->St) return 0;
  if (St >= rows.back().St) return rows.back().e;
  const auto hi = std::upper_bound(first, rows.end(), St, [](double s, const RestitutionRow& r) { return s < r.St; });
  const auto lo = hi - 1;  // lo->St <= St < hi->St
  const double w = std::log(St / lo->St) / std::log(hi->St / lo->St);
  return lo->e + w * (hi->e - lo->e);
}

}  // namespace imcol::study
