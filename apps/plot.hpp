#pragma once
// Plots are drawn by small matplotlib scripts in scripts/, run with Debian's /usr/bin/python3.
#include <filesystem>
#include <string>

namespace imcol {

/// Runs scripts/<script> DIR; prints "wrote DIR/<png>" (unless quiet) or a warning that quotes the script's
/// last output line (a Python error), the data files staying complete. Returns true if the script succeeded.
bool run_plot_script(const std::string& script, const std::filesystem::path& dir, const std::string& png, bool quiet = false);

}  // namespace imcol
