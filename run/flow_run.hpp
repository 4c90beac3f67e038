// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A flow scene's run (`imcol flow`, data/scenes/flow/): the immersed-boundary kernel stepped along the spheres'
// prescribed paths, its forces compared with the analytic references (run/flow_references.hpp) and the standard
// drag curve. Writes no files: the caller writes the force history, the snapshots and the summary.
#include <functional>
#include <optional>
#include <string>

#include "flow/field_series.hpp"
#include "flow/flow_scene.hpp"
#include "run/flow_run_result.hpp"

namespace imcol {

struct FlowRunOptions {
  bool quiet = false;  // no progress lines or warnings on stdout/stderr
  // Command-line overrides, checked like the scene keys they replace (bad values: exit 2 naming the option).
  std::optional<double> t_end;             // time.t_end
  std::optional<long> cells_per_diameter;  // grid.cells_per_diameter
  std::optional<long> levels;              // grid.levels
  std::optional<double> dt;                // time.dt
  bool allow_long = false;  // run even if the estimated wall time exceeds an hour
};

/// Runs the scene with the options' overrides. Throws InputError (overrides, a grid beyond the memory, an estimated
/// wall time beyond an hour without allow_long) before anything is allocated. The snapshots' files (snapshot_NN.csv,
/// vtk/snapshot_NN.*, flow.pvd as output.fields_format says: flow/field_series.hpp) go to `files` as the run
/// reaches them, in the kernel's frame.
FlowRunResult run_flow_scene(flow::FlowScene scene, const FlowRunOptions& opt, const flow::FileSink& files = {});

}  // namespace imcol
