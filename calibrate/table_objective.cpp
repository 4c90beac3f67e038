// SPDX-License-Identifier: BSD-3-Clause
// The e-table objective: each row one run measured as imcol sweep measures a point.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/number_text.hpp"
#include "calibrate/objective.hpp"
#include "core/errors.hpp"
#include "run/measured_run.hpp"

namespace imcol::calib {

namespace {

/// Row r's scene overrides: `overrides`, then the row's keys.
std::vector<Override> row_overrides(const MeasuredTable& m, std::size_t r, const std::vector<Override>& overrides) {
  std::vector<Override> ov = overrides;
  for (std::size_t k = 0; k < m.keys.size(); ++k) ov.push_back({m.keys[k], toml_float(m.values[r][k])});
  return ov;
}

}  // namespace

void check_table_keys(const MeasuredTable& m, const std::string& scene_path, const std::vector<Override>& overrides) {
  for (std::size_t r = 0; r < m.e.size(); ++r) {
    try {
      (void)load_scene(scene_path, row_overrides(m, r, overrides));
    } catch (const InputError& e) {
      // The scene reader names the key it refused; a table key it names is the column at fault.
      const auto it = std::find(m.keys.begin(), m.keys.end(), e.key());
      const std::string where = m.path + ":" + std::to_string(m.lines[r]);
      if (it != m.keys.end()) throw InputError(where, *it, e.problem());
      throw InputError(where, m.keys.size() == 1 ? m.keys[0] : "", "this row's scene is not valid: " + std::string(e.what()));
    }
  }
}

Evaluation evaluate_table(const MeasuredTable& m, const std::string& scene_path, const std::vector<Override>& overrides) {
  const auto t0 = std::chrono::steady_clock::now();
  Evaluation ev;
  ev.e_sim.assign(m.e.size(), std::numeric_limits<double>::quiet_NaN());
  double sum = 0;
  for (std::size_t r = 0; r < m.e.size(); ++r) {
    const std::string row = m.path + ":" + std::to_string(m.lines[r]);
    try {
      const Scene scene = load_scene(scene_path, row_overrides(m, r, overrides));
      const RunResult run = simulate_for_e(scene);
      // A collision without a rebound has e = 0 in the summary; a run without e (no collision by t_end, a rebound
      // cut short) has no e to compare: the evaluation fails.
      if (run.summary.e) ev.e_sim[r] = *run.summary.e;
      else if (ev.message.empty()) ev.message = row + ": " + e_missing_message(run.summary, scene.solver.t_end, run.scene.solver.t_end);
    } catch (const std::exception& e) {
      if (ev.message.empty()) ev.message = row + ": " + e.what();
    }
    const double d = ev.e_sim[r] - m.e[r];
    sum += d * d;
  }
  ev.ok = ev.message.empty();
  ev.residuals = m.e.size();
  ev.objective = ev.ok ? sum / static_cast<double>(m.e.size()) : std::numeric_limits<double>::infinity();
  ev.rms = std::sqrt(ev.objective);
  ev.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return ev;
}

}  // namespace imcol::calib
