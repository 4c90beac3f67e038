#pragma once
// `imcol flow SCENE [--out DIR] [--no-plot]`: runs a flow scene (data/scenes/flow/) with the immersed-boundary
// kernel and writes DIR/forces.csv, DIR/summary.json, DIR/snapshot_NN.csv (+ PNGs via scripts/plot_flow.py).
#include <string>

#include <nlohmann/json.hpp>

namespace imcol {

struct FlowCommandOptions {
  std::string out;            // default out/<scene name>
  bool plot = true;           // run scripts/plot_flow.py with /usr/bin/python3
  bool quiet = false;         // no progress lines
  double t_end = 0;           // > 0: overrides time.t_end
  int cells_per_diameter = 0; // > 0: overrides grid.cells_per_diameter
  int levels = 0;             // > 0: overrides grid.levels
  double dt = 0;              // > 0: overrides time.dt
};

/// Runs the scene; returns the summary written to DIR/summary.json.
nlohmann::ordered_json run_flow_scene(const std::string& scene_path, const FlowCommandOptions& opt);
int cmd_flow(const std::string& scene_path, const FlowCommandOptions& opt);

}  // namespace imcol
