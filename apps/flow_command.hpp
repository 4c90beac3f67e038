// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol flow SCENE [--out DIR] [--no-plot]`: runs a flow scene (data/scenes/flow/) with the immersed-boundary
// kernel (run/flow_run.hpp) and writes DIR/forces.csv, DIR/summary.json, DIR/snapshot_NN.csv (+ PNGs via
// scripts/plot_flow.py).
#include <string>

#include "run/flow_run.hpp"

namespace imcol {

struct FlowCommandOptions : FlowRunOptions {
  std::string out;   // default out/<scene name>
  bool plot = true;  // run scripts/plot_flow.py with /usr/bin/python3
};

int cmd_flow(const std::string& scene_path, const FlowCommandOptions& opt);

}  // namespace imcol
