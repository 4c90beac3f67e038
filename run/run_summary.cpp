// SPDX-License-Identifier: BSD-3-Clause
#include "run/run_summary.hpp"

#include <algorithm>
#include <cmath>

namespace imcol {

const char* to_string(Configuration c) {
  switch (c) {
    case Configuration::free_sphere: return "free sphere";
    case Configuration::sphere_wall: return "sphere-wall";
    case Configuration::sphere_sphere: return "sphere-sphere";
  }
  return "";
}

std::optional<double> RunSummary::measure_e(EMeasure m) const {
  for (const auto& [k, v] : e_measures)
    if (k == m) return v;
  return std::nullopt;
}

bool RunSummary::has(Effect x) const { return std::find(effects.begin(), effects.end(), x) != effects.end(); }

void first_contact_views(RunSummary& s) {
  s.e_measures.clear();
  s.measures_disagree.clear();
  s.energy_budget.reset();
  s.dissipated_share.clear();
  s.energy_closure.reset();
  if (s.bounces.empty()) return;
  const run::Bounce& b = s.bounces[0];
  for (const auto& [m, r] : b.e_measures) s.e_measures.push_back({m, r.e});
  s.measures_disagree = b.measures_disagree;
  s.energy_budget = b.energy_budget;
  if (!s.energy_budget) return;
  // The collision phase's dissipation by force (above 5e-4 of the impact energy) and the largest |closure| of a phase.
  double closure = 0;
  for (const auto& p : s.energy_budget->phases) {
    closure = std::max(closure, std::abs(p.closure_per_impact_energy));
    if (p.phase != run::BudgetPhase::collision) continue;
    for (std::size_t k = 0; k < model::kForceKinds; ++k)
      if (std::abs(p.dissipated_per_impact_energy[k]) > 5e-4) s.dissipated_share.push_back({model::kAllForceKinds[k], p.dissipated_per_impact_energy[k]});
  }
  s.energy_closure = closure;
}

}  // namespace imcol
