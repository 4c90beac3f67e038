// SPDX-License-Identifier: BSD-3-Clause
// The trajectory objective: its window around the measured contact, the least squares in z with the time offset
// fitted, and the run that is scored.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "calibrate/objective.hpp"
#include "core/number_text.hpp"
#include "core/errors.hpp"

namespace imcol::calib {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}


const std::vector<double>* column(const MeasuredTrajectory& m, const char* name) {
  for (std::size_t c = 0; c < m.columns.size(); ++c)
    if (m.columns[c] == name) return &m.z[c];
  return nullptr;
}

/// The measured gap at sample k (m): to the wall, or between the spheres; a sphere without a measured column is taken
/// in free flight from its initial position in the scene (a target at rest stays put).
double measured_gap(const MeasuredTrajectory& m, const Scene& sc, std::size_t k) {
  const auto* z1 = column(m, "z1");
  const auto* z2 = column(m, "z2");
  const auto& s1 = sc.spheres[0];
  const double t = m.t[k];
  const double p1 = z1 ? (*z1)[k] : s1.position + s1.velocity * t;
  if (sc.two_spheres()) {
    const auto& s2 = sc.spheres[1];
    const double p2 = z2 ? (*z2)[k] : s2.position + s2.velocity * t;
    return std::abs(p2 - p1) - (s1.diameter + s2.diameter) / 2;
  }
  if (sc.wall) return std::abs(sc.wall->position - p1) - s1.diameter / 2;
  return 0;
}

/// z of a run's column at time s: linear between rows; before the first row, the first two rows' line; after the
/// last, the last value. `j` is a search hint (the row at or before the previous s), for increasing s.
double z_at(const std::vector<std::vector<double>>& rows, std::size_t col, double s, std::size_t& j) {
  const std::size_t n = rows.size();
  if (n == 1 || s >= rows[n - 1][0]) return rows[n - 1][col];
  if (s <= rows[0][0]) {
    const double slope = (rows[1][col] - rows[0][col]) / (rows[1][0] - rows[0][0]);
    return rows[0][col] + slope * (s - rows[0][0]);
  }
  if (j >= n - 1 || rows[j][0] > s) j = 0;
  while (j + 2 < n && rows[j + 1][0] <= s) ++j;
  const auto& a = rows[j];
  const auto& b = rows[j + 1];
  const double f = (s - a[0]) / (b[0] - a[0]);
  return a[col] + f * (b[col] - a[col]);
}

}  // namespace

TrajectoryWindow trajectory_window(const MeasuredTrajectory& m, const Scene& scene, std::optional<double> before,
                                   std::optional<double> after, std::optional<double> tau_max) {
  TrajectoryWindow w;
  if (!scene.has_target()) throw InputError(scene.path, "", "a trajectory fit needs a target: a second sphere or a wall");
  if (!scene.two_spheres() && column(m, "z2"))
    throw InputError(m.path + ":" + std::to_string(m.header_line), "z2",
                     "the scene " + scene.path + " has one sphere: its run has no z2 (measure sphere 1 as z1)");
  std::size_t kc = 0;
  for (std::size_t k = 1; k < m.t.size(); ++k)
    if (measured_gap(m, scene, k) < measured_gap(m, scene, kc)) kc = k;
  w.t_contact = m.t[kc];
  // The approach speed: the scene's initial relative speed; without one (an approach under gravity), the measured
  // gap's fastest closing speed before contact.
  const auto& s1 = scene.spheres[0];
  double U = std::abs(s1.velocity - (scene.two_spheres() ? scene.spheres[1].velocity : 0.0));
  if (!(U > 0))
    for (std::size_t k = 1; k <= kc; ++k)
      U = std::max(U, (measured_gap(m, scene, k - 1) - measured_gap(m, scene, k)) / (m.t[k] - m.t[k - 1]));
  const double travel = U > 0 ? s1.diameter / U : m.t.back() - m.t.front();  // s: one diameter at the approach speed
  w.before = before.value_or(std::max(-travel, m.t.front() - w.t_contact));
  w.after = after.value_or(std::min(2 * travel, m.t.back() - w.t_contact));
  w.tau_max = tau_max.value_or(travel / 2);
  if (before && after && !(*before < *after))
    throw InputError("command line", "--window", "A = " + fmt_number(*before) + " s must be below B = " + fmt_number(*after) + " s");
  if (!(w.tau_max >= 0) || !std::isfinite(w.tau_max))
    throw InputError("command line", "--offset-max", "needs a finite number >= 0, got " + fmt_number(w.tau_max));
  const auto [k0, k1] = window_rows(m, w);
  const std::size_t n = k1 - k0;
  if (n < kMinTrajectoryRows) {
    const std::string problem = std::to_string(n) + " samples in the window [" + fmt_number(w.t_contact + w.before) + ", " +
                                fmt_number(w.t_contact + w.after) + "] s around the measured contact at " + fmt_number(w.t_contact) +
                                " s; at least " + std::to_string(kMinTrajectoryRows) + " needed";
    if (before || after) throw InputError("command line", "--window", problem);
    throw InputError(m.path, "", problem);
  }
  return w;
}

std::pair<std::size_t, std::size_t> window_rows(const MeasuredTrajectory& m, const TrajectoryWindow& w) {
  std::size_t k0 = 0, k1 = 0;
  while (k0 < m.t.size() && m.t[k0] < w.t_contact + w.before) ++k0;
  for (k1 = k0; k1 < m.t.size() && m.t[k1] <= w.t_contact + w.after;) ++k1;
  return {k0, k1};
}

namespace {

/// The run's column of each measured column; none (and ev's message) when one is missing or the run has too few rows.
std::optional<std::vector<std::size_t>> simulated_columns(const MeasuredTrajectory& m, const RunResult& run, Evaluation& ev) {
  std::vector<std::size_t> sim_col;
  for (const auto& name : m.columns) {
    const auto it = std::find(run.columns.begin(), run.columns.end(), name);
    if (it == run.columns.end()) {
      ev.objective = std::numeric_limits<double>::infinity();
      ev.message = "the run has no column " + name;
      return std::nullopt;
    }
    sim_col.push_back(static_cast<std::size_t>(it - run.columns.begin()));
  }
  if (run.rows.size() < 2 || run.columns.empty() || run.columns[0] != "t") {
    ev.objective = std::numeric_limits<double>::infinity();
    ev.message = "the run recorded fewer than two rows";
    return std::nullopt;
  }
  return sim_col;
}

/// The mean square misfit over the window's rows [k0, k1) and the measured columns, the run shifted by tau.
struct WindowMisfit {
  const MeasuredTrajectory& m;
  const RunResult& run;
  const std::vector<std::size_t>& sim_col;
  std::size_t k0, k1;
  double count;

  double operator()(double tau) const {
    double sum = 0;
    for (std::size_t c = 0; c < m.columns.size(); ++c) {
      std::size_t j = 0;
      for (std::size_t k = k0; k < k1; ++k) {
        const double r = z_at(run.rows, sim_col[c], m.t[k] - tau, j) - m.z[c][k];
        sum += r * r;
      }
    }
    return sum / count;
  }
};

/// The best (tau, f(tau)) for |tau| <= tau_max: a coarse scan, then golden-section search between the best scan
/// point's neighbours; tau = 0 when tau_max is 0.
std::pair<double, double> best_offset(const WindowMisfit& f, double tau_max) {
  constexpr int kScan = 40;  // intervals
  double best_tau = 0, best = f(0.0);
  if (!(tau_max > 0)) return {best_tau, best};
  const double h = 2 * tau_max / kScan;
  for (int i = 0; i <= kScan; ++i) {
    const double tau = -tau_max + i * h;
    const double v = f(tau);
    if (v < best) best = v, best_tau = tau;
  }
  double a = std::max(-tau_max, best_tau - h), b = std::min(tau_max, best_tau + h);
  const double g = (std::sqrt(5.0) - 1) / 2;
  double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = f(x1), f2 = f(x2);
  while (b - a > 1e-9 * tau_max) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
    }
  }
  const double tau = (a + b) / 2, v = f(tau);
  if (v < best) best = v, best_tau = tau;
  return {best_tau, best};
}

}  // namespace

Evaluation trajectory_objective(const MeasuredTrajectory& m, const TrajectoryWindow& w, const RunResult& run) {
  Evaluation ev;
  const auto sim_col = simulated_columns(m, run, ev);
  if (!sim_col) return ev;
  const auto [k0, k1] = window_rows(m, w);
  ev.residuals = (k1 - k0) * m.columns.size();
  const WindowMisfit f{m, run, *sim_col, k0, k1, static_cast<double>(ev.residuals)};
  const auto [best_tau, best] = best_offset(f, w.tau_max);
  ev.ok = std::isfinite(best);
  ev.objective = ev.ok ? best : std::numeric_limits<double>::infinity();
  ev.rms = std::sqrt(ev.objective);
  ev.tau = best_tau;
  if (!ev.ok) ev.message = "the residual is not finite";
  return ev;
}

Scene trajectory_scene(const TrajectoryWindow& w, const std::string& scene_path, const std::vector<Override>& overrides) {
  // The run covers the window's end at the largest offset, and follows every bounce (measure.bounces = "first"
  // would end it soon after the first rebound); a run that ends at rest earlier holds its last value.
  std::vector<Override> ov = overrides;
  ov.push_back({"solver.t_end", toml_float(w.t_contact + w.after + w.tau_max)});
  ov.push_back({"measure.bounces", "\"all\""});
  return load_scene(scene_path, ov);
}

Evaluation evaluate_trajectory(const MeasuredTrajectory& m, const TrajectoryWindow& w, const std::string& scene_path,
                               const std::vector<Override>& overrides) {
  const auto t0 = std::chrono::steady_clock::now();
  Evaluation ev;
  try {
    ev = trajectory_objective(m, w, simulate(trajectory_scene(w, scene_path, overrides), false, Recording::kinematics));
  } catch (const std::exception& e) {
    ev = Evaluation{};
    ev.message = e.what();
  }
  if (!ev.ok) ev.objective = std::numeric_limits<double>::infinity(), ev.rms = ev.objective;
  ev.wall_s = seconds_since(t0);
  return ev;
}

}  // namespace imcol::calib
