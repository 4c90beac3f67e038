// SPDX-License-Identifier: BSD-3-Clause
#include "core/close_names.hpp"

#include <algorithm>

namespace imcol {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  // d[i][j]: the edits from a's first i characters to b's first j, three rows kept (a swap looks two back).
  std::vector<std::vector<std::size_t>> d(3, std::vector<std::size_t>(m + 1));
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    auto& row = d[i % 3];
    const auto& up = d[(i - 1) % 3];
    row[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      row[j] = std::min({up[j] + 1, row[j - 1] + 1, up[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) row[j] = std::min(row[j], d[(i - 2) % 3][j - 2] + 1);
    }
  }
  return d[n % 3][m];
}

std::size_t allowed_edits(std::size_t size) { return size <= 4 ? 1 : std::max<std::size_t>(2, size / 3); }

std::vector<std::string> close_names(const std::string& name, const std::vector<std::string>& candidates, std::size_t most) {
  std::vector<std::pair<std::size_t, std::string>> scored;
  const std::size_t allowed = allowed_edits(name.size());
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    if (d > 0 && d <= allowed) scored.emplace_back(d, c);
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < scored.size() && out.size() < most; ++i) out.push_back(scored[i].second);
  return out;
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates) {
  const auto close = close_names(name, candidates, 2);
  if (close.empty()) return "";
  std::string s = "; did you mean '" + close[0] + "'";
  if (close.size() > 1) s += " or '" + close[1] + "'";
  return s + "?";
}

}  // namespace imcol
