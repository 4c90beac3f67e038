// SPDX-License-Identifier: BSD-3-Clause
#include "study/sweep_columns.hpp"

namespace imcol::study {

const std::vector<SweepColumn>& sweep_columns() {
  using P = const SweepPoint&;
  using V = std::optional<double>;
  // A failed point has no numbers.
  static const std::vector<SweepColumn> cols = {
      {"St", [](P p) { return p.ok ? p.summary.St : V(); }, nullptr},
      {"St_B_table_6_1", [](P p) { return p.ok ? p.summary.St_B_table_6_1 : V(); }, nullptr},
      {"St_B_eq_6_2", [](P p) { return p.ok ? p.summary.St_B_eq_6_2 : V(); }, nullptr},
      {"St_L", [](P p) { return p.ok ? p.summary.St_L : V(); }, nullptr},
      {"St_initial", [](P p) { return p.ok ? p.summary.St_initial : V(); }, nullptr},
      {"Re", [](P p) { return p.ok ? p.summary.Re : V(); }, nullptr},
      {"e", [](P p) { return p.ok ? p.summary.e : V(); }, nullptr},
      {"e_instant", [](P p) { return p.ok ? p.summary.e_instant : V(); }, nullptr},
      // The named measures of e (docs/bounces.md); `e` is the one e_is names (measure.e).
      {"e_fit_distance", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::fit_distance) : V(); }, nullptr},
      {"e_at_gap", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::at_gap) : V(); }, nullptr},
      {"e_peak_rebound", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::peak_rebound) : V(); }, nullptr},
      {"separated", [](P p) { return p.ok ? V(p.summary.separated ? 1.0 : 0.0) : V(); }, nullptr},
      {"min_gap_m", [](P p) { return p.ok ? p.summary.min_gap_m : V(); }, nullptr},
      {"steps", [](P p) { return p.ok ? V(static_cast<double>(p.summary.solver.stats.steps)) : V(); }, nullptr},
      {"rhs_evals", [](P p) { return p.ok ? V(static_cast<double>(p.summary.solver.stats.rhs_evals)) : V(); }, nullptr},
      {"wall_time_s", [](P p) { return p.ok ? V(p.summary.wall_time_s) : V(); }, nullptr},
      {"status", nullptr, [](P p) { return std::string(p.ok ? "ok" : "failed"); }},
      {"message", nullptr, [](P p) { return p.message; }},
      {"e_is", nullptr, [](P p) { return p.ok ? std::string(to_string(p.summary.e_is)) : std::string(); }},
      {"e_status", nullptr, [](P p) { return p.ok ? e_status(p.summary) : std::string(); }},
      {"e_fit_time", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::fit_time) : V(); }, nullptr},
      {"e_yang_hunt_2006", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::yang_hunt_2006) : V(); }, nullptr},
      {"e_joseph_2001", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::joseph_2001) : V(); }, nullptr},
      {"e_gondret_2002", [](P p) { return p.ok ? p.summary.measure_e(EMeasure::gondret_2002) : V(); }, nullptr},
  };
  return cols;
}

}  // namespace imcol::study
