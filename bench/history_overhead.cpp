// SPDX-License-Identifier: BSD-3-Clause
// What the history force costs at equal accuracy, both measured in the same run. For each scene, a ladder of rtol
// (atol the scene's) with the history effect (the scene's evaluator and fit) and without it, each rung's e against its
// own reference (history: soe at rtol 1e-12 with fit tolerance 1e-10; without: rtol 1e-12). Time: the median over
// `repeat` rounds of the integration's wall time (summary wall_time_s, as `imcol bench`), the two ladders interleaved
// rung by rung. At equal error: for each rung without history, the cheapest rung with history whose error is no larger
// (a step function, so the ratio is an upper bound), and the ratio of their times.
// Usage: imcol_bench_history_overhead [--repeat N] [--csv FILE] [SCENE ...]   (default scenes: default seed_run2)
// A benchmark, not a test: its times depend on the machine and its load.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "core/scene_files.hpp"
#include "run/simulate.hpp"

namespace {

using namespace imcol;

const std::vector<std::string> kRtols = {"1e-5", "3e-6", "1e-6", "3e-7", "1e-7", "3e-8", "1e-8", "3e-9", "1e-9"};

struct Rung {
  std::string rtol;
  double e = NAN, err = NAN, ms = NAN;
  long steps = 0;
  std::vector<double> times;  // ms, one per round
};

/// The scene's effects without history, as an override of `effects`.
Override without_history(const std::string& scene) {
  std::string list = "[";
  for (Effect x : load_scene(scene).effects)
    if (x != Effect::history) list.append("\"").append(to_string(x)).append("\", ");
  return {"effects", list + "]"};
}

double e_of(const RunResult& r) { return r.summary.e.value_or(NAN); }

double reference_e(const std::string& scene, std::vector<Override> ov, bool history) {
  ov.push_back({"solver.rtol", "1e-12"});
  if (history) {
    ov.push_back({"history.evaluator", "\"soe\""});
    ov.push_back({"history.tolerance", "1e-10"});
  }
  return e_of(simulate(load_scene(scene, ov), false, Recording::kinematics));
}

void time_rung(const std::string& scene, const std::vector<Override>& base, Rung& r) {
  auto ov = base;
  ov.push_back({"solver.rtol", r.rtol});
  const RunResult res = simulate(load_scene(scene, ov));
  r.e = e_of(res);
  r.steps = res.summary.solver.stats.steps;
  r.times.push_back(1e3 * res.summary.wall_time_s);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() / 2];
}

/// The cheapest rung with history whose error is at most `err`.
std::optional<Rung> cheapest_within(const std::vector<Rung>& on, double err) {
  std::optional<Rung> best;
  for (const auto& r : on)
    if (r.err <= err && (!best || r.ms < best->ms)) best = r;
  return best;
}

void print_scene(const std::string& name, const std::vector<Rung>& on, const std::vector<Rung>& off, std::ostream* csv) {
  std::cout << "\nscene " << name << "\n"
            << "      rtol |  with history: err e   steps     ms |  without: err e   steps     ms | same rtol | equal error (rtol with)\n";
  for (std::size_t k = 0; k < on.size(); ++k) {
    const auto& a = on[k];
    const auto& b = off[k];
    const auto eq = cheapest_within(on, b.err);
    std::cout << std::setw(10) << a.rtol << " | " << std::scientific << std::setprecision(1) << std::setw(19) << a.err << std::fixed
              << std::setw(8) << a.steps << std::setprecision(3) << std::setw(7) << a.ms << " | " << std::scientific << std::setprecision(1)
              << std::setw(14) << b.err << std::fixed << std::setw(8) << b.steps << std::setprecision(3) << std::setw(7) << b.ms << " | "
              << std::setprecision(2) << std::setw(8) << a.ms / b.ms << "x | ";
    if (eq) std::cout << std::setw(6) << eq->ms / b.ms << "x (" << eq->rtol << ")";
    else std::cout << "     - (no rung as accurate)";
    std::cout << "\n";
    if (csv)
      *csv << name << "," << a.rtol << "," << a.err << "," << a.ms << "," << a.steps << "," << b.err << "," << b.ms << "," << b.steps
           << "," << (eq ? eq->ms / b.ms : NAN) << "\n";
  }
}

void run_scene(const std::string& scene, int repeat, std::ostream* csv) {
  const std::vector<Override> with_h = {}, without_h = {without_history(scene)};
  const double ref_on = reference_e(scene, with_h, true), ref_off = reference_e(scene, without_h, false);
  std::vector<Rung> on, off;
  for (const auto& r : kRtols) {
    Rung rung;
    rung.rtol = r;
    on.push_back(rung);
    off.push_back(rung);
  }
  for (std::size_t k = 0; k < kRtols.size(); ++k) {
    time_rung(scene, with_h, on[k]);  // warm-up: the exponential fit is built once per process
    time_rung(scene, without_h, off[k]);
    on[k].times.clear(), off[k].times.clear();
  }
  for (int round = 0; round < repeat; ++round)
    for (std::size_t k = 0; k < kRtols.size(); ++k) {
      time_rung(scene, with_h, on[k]);
      time_rung(scene, without_h, off[k]);
    }
  for (std::size_t k = 0; k < kRtols.size(); ++k) {
    on[k].ms = median(on[k].times), off[k].ms = median(off[k].times);
    on[k].err = std::abs(on[k].e - ref_on), off[k].err = std::abs(off[k].e - ref_off);
  }
  print_scene(load_scene(scene).name, on, off, csv);
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 11;
  std::string csv_path;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::stoi(argv[++i]));
    else if (a == "--csv" && i + 1 < argc) csv_path = argv[++i];
    else scenes.push_back(a);
  }
  if (scenes.empty()) scenes = {"default", "seed_run2"};
  std::ofstream csv;
  if (!csv_path.empty()) {
    csv.open(csv_path);
    csv << "scene,rtol,err_with,ms_with,steps_with,err_without,ms_without,steps_without,ratio_equal_error\n";
  }
  std::cout << "The history force's cost: median of " << repeat << " interleaved rounds, ms of the integration (wall_time_s)\n";
  try {
    for (const auto& s : scenes) run_scene(find_scene(s), repeat, csv_path.empty() ? nullptr : &csv);
  } catch (const std::exception& e) {
    std::cerr << "imcol_bench_history_overhead: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
