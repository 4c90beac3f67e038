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

namespace imcol {

namespace fs = std::filesystem;

int cmd_flow(const std::string& scene_path, const FlowCommandOptions& opt) {
  const flow::FlowScene sc = flow::load_flow_scene(scene_path);
  OutputUnit unit(opt.out, fs::path("out") / sc.name, scene_path);
  const auto files = [&](const std::string& name, const std::string& content) { write_file_atomic(unit.dir() / name, content); };
  FlowRunResult r = run_flow_scene(sc, opt, files);
  auto& j = r.summary;
  j["run"] = unit.run();
  write_file_atomic(unit.dir() / "forces.csv", r.forces_csv);
  write_file_atomic(unit.dir() / "summary.json", j.dump(2) + "\n");
  std::cout << std::setprecision(5);
  std::cout << "Re = " << j["Re"].get<double>() << "  C_D = " << j["drag_coefficient"].get<double>();
  if (!j["drag_coefficient_standard"].is_null())
    std::cout << "  (steady; standard curve " << j["drag_coefficient_standard"].get<double>() << ", error " << std::setprecision(3)
              << j["drag_error_percent"].get<double>() << " %)";
  else if (!j["drag_settled"].get<bool>() && j["forces_N"].size() == 1 && !j.contains("oscillating"))
    std::cout << "  (not settled: changed " << std::setprecision(3) << j["drag_change_last_tenth_percent"].get<double>()
              << " % over the last tenth of the run; not compared with the steady standard curve)";
  std::cout << std::setprecision(5) << "  F/(6 pi mu a U) = " << j["stokes_drag_ratio"].get<double>() << "\n";
  if (j.contains("wake_length_D") && j["wake_length_D"].is_number()) std::cout << "wake length = " << j["wake_length_D"].get<double>() << " D\n";
  if (j.contains("f_sim_vs_f_thr")) {
    for (const auto& r : j["f_sim_vs_f_thr"]) {
      if (r.contains("F_wall"))
        std::cout << "wall gap " << r["gap_D"].get<double>() << " D: F1 = " << r["F1"].get<double>() << " (f_THR Brenner " << r["F_THR1"].get<double>()
                  << ", " << std::setprecision(3) << 100 * (r["F1"].get<double>() / r["F_THR1"].get<double>() - 1) << std::setprecision(5)
                  << " %), wall " << r["F_wall"].get<double>() << " N" << (r["resolved"].get<bool>() ? "" : "  [not resolved: gap below 3 cells]")
                  << "\n";
      else
        std::cout << "gap " << r["gap_D"].get<double>() << " D: F1 = " << r["F1"].get<double>() << " (f_THR " << r["F_THR1"].get<double>()
                  << "), F2 = " << r["F2"].get<double>() << " (f_THR " << r["F_THR2"].get<double>() << ") N"
                  << (r["resolved"].get<bool>() ? "" : "  [not resolved: gap below 3 cells]") << "\n";
    }
  }
  if (j.contains("oscillating"))
    std::cout << "oscillating sphere vs unsteady Stokes (delta/a = " << j["oscillating"]["delta_over_a"].get<double>()
              << "): max error over the last period " << 100 * j["oscillating"]["max_error_last_period_rel_amplitude"].get<double>()
              << " % of the force amplitude\n";
  if (j.contains("impulsive_start"))
    std::cout << "impulsive start vs Stokes + Basset: max relative error " << j["impulsive_start"]["max_rel_error"].get<double>()
              << " for " << j["impulsive_start"]["window_t"][0].get<double>() << " <= t <= "
              << j["impulsive_start"]["window_t"][1].get<double>() << " s (0.8 <= nu t / a^2 <= 4)\n";
  std::cout << "steps " << j["steps"].get<long>() << ", wall " << j["wall_time_s"].get<double>() << " s ("
            << j["ms_per_step"].get<double>() << " ms/step)\n";
  if (opt.plot) {
    std::cout.flush();
    run_plot_script("plot_flow.py", unit, "forces.png");  // also snapshot_NN.png
    if (j.contains("f_sim_vs_f_thr") && !j.contains("wall"))
      run_plot_script("plot_force_vs_gap.py", unit, "forces_vs_gap.png");  // seed Fig. 6.4 (a wall: plot_flow.py draws it)
  }
  unit.commit();
  std::cout << "wrote " << (unit.target() / "forces.csv").string() << ", " << (unit.target() / "summary.json").string() << ", snapshots\n";
  return 0;
}

}  // namespace imcol
