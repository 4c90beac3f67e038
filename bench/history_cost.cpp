// SPDX-License-Identifier: BSD-3-Clause
// What the history force's accuracy costs: the sum-of-exponentials evaluator against direct
// product integration on the rising-sphere scene (exact solution known, MODEL.md §2.3).
//  1. At 100 relaxation times: error against the closed form and wall time for a ladder of settings
//     of each evaluator; the cheapest run of each that reaches a given error, and their time ratio.
//  2. How each cost grows with the length of the run (fixed settings per evaluator).
// Usage: imcol_history_cost [SCENE] (default data/scenes/rising_sphere.toml). A benchmark, not a test.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

#include "run/simulate.hpp"
#include "contact/history_kernel.hpp"
#include "core/materials.hpp"
#include "core/scene.hpp"

namespace {

using namespace imcol;

struct Result {
  double error, ms;
  long steps;
};

std::string num(double v) {
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}

/// α [1/s], γ [1/√s] and the forcing f [m/s²] of MODEL.md §2.3's settling problem for the scene's sphere.
struct Exact {
  double alpha, gamma, f;
  explicit Exact(const Scene& sc) {
    const auto& s = sc.spheres.at(0);
    const double a = s.diameter / 2, rp = s.density, rf = sc.fluid->density, mu = sc.fluid->viscosity;
    alpha = 9 * mu / (a * a * (2 * rp + rf));
    gamma = 9 * std::sqrt(rf * mu) / (a * (2 * rp + rf));
    f = 2 * (rp - rf) * sc.gravity / (2 * rp + rf);
  }
};

Result run_case(const std::string& path, std::vector<Override> ov, double relax_times, int repeat = 3) {
  const auto [alpha, gamma, f] = Exact(load_scene(path, ov));
  const double t_end = relax_times / alpha;
  ov.push_back({"solver.t_end", num(t_end)});
  ov.push_back({"output.dt", num(t_end / 100)});
  const Scene sc = load_scene(path, ov);
  std::vector<double> times;
  RunResult r;
  for (int k = 0; k < repeat; ++k) {
    r = simulate(sc);
    times.push_back(r.summary.wall_time_s + r.summary.setup_time_s);
  }
  std::sort(times.begin(), times.end());
  double worst = 0;
  for (const auto& row : r.rows)
    if (row[0] > 0) worst = std::max(worst, std::abs(row[2] - f * contact::basset_settling(alpha, gamma, row[0])) / std::abs(f / alpha));
  return {worst, 1e3 * times[times.size() / 2], r.summary.solver.stats.steps};
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : data_dir() + "/scenes/rising_sphere.toml";
  std::cout << std::setprecision(3);
  std::cout << "scene " << path << "; error = max |u - u_exact| / u_terminal; time = median of 3 (setup + integration)\n";
  std::cout << "\n1. 100 relaxation times\n";
  std::cout << std::setw(10) << "evaluator" << std::setw(22) << "setting" << std::setw(12) << "error" << std::setw(10)
            << "steps" << std::setw(10) << "ms" << "\n";
  struct Entry { std::string ev, setting; Result r; };
  std::vector<Entry> all;
  for (double tol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9}) {
    const Result r = run_case(path, {{"history.evaluator", "\"soe\""}, {"history.tolerance", num(tol)}, {"solver.rtol", num(tol / 10)},
                                {"solver.atol", num(tol / 100)}}, 100);
    std::ostringstream st;
    st << "tol " << tol << " rtol " << tol / 10;
    all.push_back({"soe", st.str(), r});
  }
  const double alpha = Exact(load_scene(path)).alpha;
  for (int n : {250, 500, 1000, 2000, 4000, 8000}) {
    const double dt = 100 / alpha / n;  // 100 relaxation times in n steps
    const Result r = run_case(path, {{"history.evaluator", "\"direct\""}, {"history.direct_step", num(dt)},
                                {"solver.rtol", "1e-10"}, {"solver.atol", "1e-12"}}, 100, 1);
    all.push_back({"direct", "N = " + std::to_string(n) + " steps", r});
  }
  for (const auto& e : all)
    std::cout << std::setw(10) << e.ev << std::setw(22) << e.setting << std::setw(12) << e.r.error << std::setw(10)
              << e.r.steps << std::setw(10) << e.r.ms << "\n";
  std::cout << "\ncheapest run reaching each error:\n" << std::setw(10) << "error" << std::setw(12) << "soe ms"
            << std::setw(12) << "direct ms" << std::setw(14) << "direct/soe" << "\n";
  for (double target : {1e-3, 1e-4, 1e-5}) {
    double best[2] = {INFINITY, INFINITY};
    for (const auto& e : all)
      if (e.r.error <= target) best[e.ev == "soe" ? 0 : 1] = std::min(best[e.ev == "soe" ? 0 : 1], e.r.ms);
    std::cout << std::setw(10) << target << std::setw(12) << best[0] << std::setw(12) << best[1] << std::setw(14)
              << best[1] / best[0] << "\n";
  }

  std::cout << "\n2. cost against run length (soe tol 1e-6; direct with the fixed step of N = 1000 per 100 relaxation times)\n";
  std::cout << std::setw(12) << "relax times" << std::setw(12) << "soe ms" << std::setw(10) << "steps" << std::setw(12)
            << "direct ms" << std::setw(10) << "steps" << std::setw(12) << "soe error" << std::setw(12) << "dir error" << "\n";
  const double dt = 100 / alpha / 1000;
  for (double L : {25.0, 50.0, 100.0, 200.0, 400.0}) {
    const Result so = run_case(path, {{"history.evaluator", "\"soe\""}, {"history.tolerance", "1e-6"}, {"solver.rtol", "1e-7"},
                                 {"solver.atol", "1e-8"}}, L);
    const Result di = run_case(path, {{"history.evaluator", "\"direct\""}, {"history.direct_step", num(dt)},
                                 {"solver.rtol", "1e-7"}, {"solver.atol", "1e-8"}}, L, 1);
    std::cout << std::setw(12) << L << std::setw(12) << so.ms << std::setw(10) << so.steps << std::setw(12) << di.ms
              << std::setw(10) << di.steps << std::setw(12) << so.error << std::setw(12) << di.error << "\n";
  }
  return 0;
}
