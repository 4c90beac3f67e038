#pragma once
// One collision run: build the model the scene calls for, integrate, measure, report.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace imcol {

struct RunResult {
  Scene scene;
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;  // trajectory samples
  nlohmann::ordered_json summary;
  std::vector<std::pair<std::string, std::string>> files;  // further files: name in the output directory, content
};

/// Runs one scene. Throws InputError (bad scene), SolverError (integration failed).
RunResult simulate(const Scene& scene);

/// Called after every flow step of a coupled run with (t, t_end, flow steps); none for the reduced-order model.
using ProgressFn = std::function<void(double, double, long)>;
RunResult simulate(const Scene& scene, const ProgressFn& progress);

/// DIR/trajectory.csv and DIR/summary.json (and a coupled run's flow fields), each written completely or not at all.
void write_outputs(const RunResult& r, const std::filesystem::path& dir);

/// A short human-readable summary.
std::string human_summary(const RunResult& r);

}  // namespace imcol
