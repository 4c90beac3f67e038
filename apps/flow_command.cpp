// SPDX-License-Identifier: BSD-3-Clause
#include "apps/flow_command.hpp"

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>

#include "apps/output_unit.hpp"
#include "apps/plot.hpp"
#include "core/report.hpp"
#include "flow/flow_scene.hpp"
#include "run/flow_run.hpp"
#include "run/flow_run_json.hpp"

namespace imcol {

namespace fs = std::filesystem;

namespace {

/// The drag line: C_D with the standard curve when settled, else how far it still changed; F / 6πμaU.
void print_drag(const FlowRunResult& r) {
  const FlowDragComparison& d = r.drag;
  std::cout << std::setprecision(5);
  std::cout << "Re = " << r.Re << "  C_D = " << d.coefficient;
  if (d.standard)
    std::cout << "  (steady; standard curve " << *d.standard << ", error " << std::setprecision(3) << *d.error_percent << " %)";
  else if (!d.settled && r.forces_N.size() == 1 && !r.oscillating)
    std::cout << "  (not settled: changed " << std::setprecision(3) << d.change_last_tenth_percent
              << " % over the last tenth of the run; not compared with the steady standard curve)";
  std::cout << std::setprecision(5) << "  F/(6 pi mu a U) = " << d.stokes_drag_ratio << "\n";
  if (r.one_sphere && r.one_sphere->wake_length_D) std::cout << "wake length = " << *r.one_sphere->wake_length_D << " D\n";
}

/// f_SIM against f_THR at the report gaps.
void print_gap_forces(const std::vector<FlowGapForces>& rows) {
  for (const auto& g : rows) {
    if (g.F_wall)
      std::cout << "wall gap " << g.gap_D << " D: F1 = " << g.F1 << " (f_THR Brenner " << g.F_THR1 << ", " << std::setprecision(3)
                << 100 * (g.F1 / g.F_THR1 - 1) << std::setprecision(5) << " %), wall " << *g.F_wall << " N"
                << (g.resolved ? "" : "  [not resolved: gap below 3 cells]") << "\n";
    else
      std::cout << "gap " << g.gap_D << " D: F1 = " << g.F1 << " (f_THR " << g.F_THR1 << "), F2 = " << *g.F2 << " (f_THR " << *g.F_THR2
                << ") N" << (g.resolved ? "" : "  [not resolved: gap below 3 cells]") << "\n";
  }
}

/// The comparisons with the unsteady references, and the steps.
void print_references_and_steps(const FlowRunResult& r) {
  if (r.oscillating)
    std::cout << "oscillating sphere vs unsteady Stokes (delta/a = " << r.oscillating->delta_over_a << "): max error over the last period "
              << 100 * r.oscillating->max_error_rel_amplitude << " % of the force amplitude\n";
  if (r.one_sphere && r.one_sphere->impulsive_start) {
    const FlowImpulsiveStart& b = *r.one_sphere->impulsive_start;
    std::cout << "impulsive start vs Stokes + Basset: max relative error " << b.max_rel_error << " for " << b.window_t0 << " <= t <= "
              << b.window_t1 << " s (0.8 <= nu t / a^2 <= 4)\n";
  }
  std::cout << "steps " << r.steps << ", wall " << r.wall_time_s << " s (" << r.ms_per_step << " ms/step)\n";
}

}  // namespace

int cmd_flow(const std::string& scene_path, const FlowCommandOptions& opt) {
  const flow::FlowScene sc = flow::load_flow_scene(scene_path);
  OutputUnit unit(opt.out, fs::path("out") / sc.name, scene_path);
  const auto files = [&](const std::string& name, const std::string& content) { write_file_atomic(unit.dir() / name, content); };
  const FlowRunResult r = run_flow_scene(sc, opt, files);
  nlohmann::ordered_json j = flow_summary_json(r);
  j["run"] = unit.run();
  write_file_atomic(unit.dir() / "forces.csv", r.forces_csv);
  write_file_atomic(unit.dir() / "summary.json", j.dump(2) + "\n");
  print_drag(r);
  if (r.gap_forces) print_gap_forces(*r.gap_forces);
  print_references_and_steps(r);
  if (opt.plot) {
    std::cout.flush();
    run_plot_script("plot_flow.py", unit, "forces.png");  // also snapshot_NN.png
    if (r.gap_forces && !r.wall) run_plot_script("plot_force_vs_gap.py", unit, "forces_vs_gap.png");  // seed Fig. 6.4 (a wall: plot_flow.py draws it)
  }
  unit.commit();
  std::cout << "wrote " << (unit.target() / "forces.csv").string() << ", " << (unit.target() / "summary.json").string() << ", snapshots\n";
  return 0;
}

}  // namespace imcol
