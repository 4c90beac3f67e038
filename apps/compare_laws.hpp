// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol laws`: one scene run once per solid contact law (contact.law), side by side; optionally at each point of a
// sweep of one quantity (e against St per law).
#include <string>
#include <vector>

#include "apps/sweep.hpp"
#include "core/scene.hpp"

namespace imcol {

struct LawsCompareOptions {
  std::vector<std::string> laws;  // contact.law names; empty = every shipped law
  std::string out;                // default out/<scene>-laws (a sweep: out/<scene>-laws_<quantity>)
  bool plot = true;
  SweepOptions sweep;             // sweep.vary empty: the scene alone; else vary, from, to, points, spacing
};

/// Runs the scene (or each sweep point) with each law; a law that refuses the scene, or whose run fails, gets a row
/// saying why. Prints the table and writes DIR/laws.csv, DIR/laws.json and DIR/laws.png (matplotlib), and for one
/// scene DIR/laws_traces.csv. Returns 0 if at least one law ran; otherwise throws a solver failure (exit 3) or the
/// first law's refusal (exit 2).
int compare_laws(const std::string& scene_path, const std::vector<Override>& overrides, const LawsCompareOptions& opt);

}  // namespace imcol
