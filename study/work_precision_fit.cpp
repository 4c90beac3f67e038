// SPDX-License-Identifier: BSD-3-Clause
#include "study/work_precision_fit.hpp"

#include <cmath>

namespace imcol::study {

std::optional<double> loglog_slope(const std::vector<std::pair<double, double>>& xy) {
  if (xy.size() < 3) return std::nullopt;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (auto [x, y] : xy) {
    const double lx = std::log10(x), ly = std::log10(y);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double n = static_cast<double>(xy.size()), d = n * sxx - sx * sx;
  if (!(std::abs(d) > 0)) return std::nullopt;
  return (n * sxy - sx * sy) / d;
}

std::vector<ObservedOrder> observed_orders(const std::vector<LadderConfig>& configs, const std::vector<WorkPrecisionRow>& rows,
                                           double floor) {
  std::vector<ObservedOrder> orders;
  for (const auto& c : configs) {
    std::vector<std::pair<double, double>> by_tol, by_steps;
    for (const auto& p : rows)
      if (p.cfg.label() == c.label() && p.ok && p.err_e > floor) {
        by_tol.push_back({c.direct() ? p.direct_step : p.rtol, p.err_e});
        by_steps.push_back({static_cast<double>(p.steps), p.err_e});
      }
    ObservedOrder o;
    o.config = c.label();
    o.vs = c.direct() ? "direct_step" : "rtol";
    o.exponent = loglog_slope(by_tol);
    if (const auto q = loglog_slope(by_steps)) o.order_in_steps = -*q;
    o.points = by_tol.size();
    orders.push_back(o);
  }
  return orders;
}

std::vector<CheapestSetting> cheapest_settings(const std::vector<WorkPrecisionRow>& rows) {
  std::vector<CheapestSetting> cheapest;
  for (double target : {1e-3, 1e-6, 1e-9}) {
    CheapestSetting best{target, std::nullopt};
    for (std::size_t i = 0; i < rows.size(); ++i) {
      bool good = rows[i].ok && rows[i].err_e <= target;
      for (std::size_t j = i + 1; good && j < rows.size() && rows[j].cfg.label() == rows[i].cfg.label(); ++j)
        good = rows[j].ok && rows[j].err_e <= target;
      if (good && (!best.row || rows[i].ms < rows[*best.row].ms)) best.row = i;
    }
    cheapest.push_back(best);
  }
  return cheapest;
}

}  // namespace imcol::study
