// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One collision run (the layer above coupling/): build the model the scene calls for, integrate (alone or
// coupled to the flow kernel), measure the contacts, report. Used by every command, the benchmarks and the tests.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "flow/field_series.hpp"
#include "run/run_summary.hpp"

namespace imcol {

struct RunResult {
  Scene scene;
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;  // trajectory samples
  std::vector<std::vector<double>> contact_rows;  // the same columns at every solver step while the gap < 3 δ_SS (full recording, history force)
  RunSummary summary;                   // what the run measured, typed
  nlohmann::ordered_json summary_json;    // summary.json: the same values (and more) under their names
};

/// What the trajectory rows carry. `kinematics`: positions, velocities and events only (what e is measured from);
/// the forces are evaluated only where the model needs them to end the run (at rest), so that sweeps skip their
/// cost; the summary's max_contact_force_N and max_history_force_N are then null, and it has no energy budget.
enum class Recording { full, kinematics };

/// Runs one scene. Throws InputError (bad scene), SolverError (integration failed).
/// `progress`: a run still going after 2 s shows a progress line on a terminal (stderr).
/// `fields`: receives a coupled run's flow-field files as they are made (flow/field_series.hpp); without it a coupled
/// run computes no flow fields (flow.fields applies to the runs that write them).
RunResult simulate(const Scene& scene, bool progress = false, Recording recording = Recording::full, const flow::FileSink& fields = {});

/// DIR/trajectory.csv and DIR/summary.json, each written completely or not at all (the flow fields went to simulate's sink).
void write_outputs(const RunResult& r, const std::filesystem::path& dir);

/// A short human-readable summary.
std::string human_summary(const RunResult& r);

}  // namespace imcol
