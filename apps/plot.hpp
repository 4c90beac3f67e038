// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Plots are drawn by small matplotlib scripts in scripts/, run with Debian's /usr/bin/python3.
#include <filesystem>
#include <string>

#include "apps/output_unit.hpp"

namespace imcol {

/// Runs scripts/<script> on the unit's staged folder; prints "wrote TARGET/<png>" (unless quiet) or a warning that
/// quotes the script's last output line (a Python error), the data files staying complete. True if it succeeded.
bool run_plot_script(const std::string& script, const OutputUnit& unit, const std::string& png, bool quiet = false);

}  // namespace imcol
