#pragma once
// `imcol flow SCENE [--out DIR] [--no-plot]`: runs a flow scene (data/scenes/flow/) with the immersed-boundary
// kernel and writes DIR/forces.csv, DIR/summary.json, DIR/snapshot_NN.csv (+ PNGs via scripts/plot_flow.py).
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace imcol {

struct FlowCommandOptions {
  std::string out;            // default out/<scene name>
  bool plot = true;           // run scripts/plot_flow.py with /usr/bin/python3
  bool quiet = false;         // no progress lines
  // Command-line overrides, checked like the scene keys they replace (bad values: exit 2 naming the option).
  std::optional<double> t_end;            // time.t_end
  std::optional<long> cells_per_diameter; // grid.cells_per_diameter
  std::optional<long> levels;             // grid.levels
  std::optional<double> dt;               // time.dt
  bool allow_long = false;    // run even if the estimated wall time exceeds an hour
};

/// Runs the scene and writes its files into `dir` (opt.out is not read); returns the summary written to
/// dir/summary.json, which holds `run` when that is given.
nlohmann::ordered_json run_flow_scene(const std::string& scene_path, const FlowCommandOptions& opt, const std::filesystem::path& dir,
                                      const nlohmann::ordered_json& run = nullptr);
int cmd_flow(const std::string& scene_path, const FlowCommandOptions& opt);

}  // namespace imcol
