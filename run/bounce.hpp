// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One contact of a run as typed values (summary.json `bounces`, docs/bounces.md): its times, e by the measure
// measure.e names, every named measure's e and what it read, the apex after the rebound and the collision's energy
// budget (docs/energy.md). Velocities in m/s, gaps in m, times in s, energies in J. run/bounce_json.hpp writes them.
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/choices.hpp"
#include "model/force_work.hpp"

namespace imcol::run {

/// A sphere's fitted position over a measure's stretch: z(t) = z + u (t − t_ref) + ½ a (t − t_ref)².
struct FittedPosition {
  double t_ref_s = 0, z_m = 0, u_m_s = 0, a_m_s2 = 0;
};

/// A measure's stretch [t0, t1] and each sphere's fitted position in it (none where the fit failed; z2: pairs only).
struct FittedStretch {
  double t0_s = 0, t1_s = 0;
  std::optional<FittedPosition> z1, z2;
  bool pair = false;
};

/// The end slopes of contact_ends against U_rel at the δ_SS crossings, in units of the impact speed.
struct EndMismatch {
  std::optional<double> approach, rebound;
};

/// One named measure of e at one contact. Each measure fills its own fields; the others stay empty and are not written.
struct MeasureResult {
  bool velocities = true;  // impact_velocity_m_s and rebound_velocity_m_s are reported (all measures but instant)
  std::optional<double> impact_velocity_m_s, rebound_velocity_m_s, e, e_raw;
  std::optional<std::string> note;  // why e was clipped to 0 (with e_raw)
  std::optional<double> gap_m, distance_m, approach_distance_m, rebound_distance_m, window_s, shortened_from_s;
  std::optional<std::string> shortened_by;
  std::optional<bool> cut_by_end_of_run;
  std::optional<EndMismatch> end_mismatch;
  std::optional<std::string> warning;
  std::optional<double> impact_speed_m_s, rebound_speed_m_s;
  bool stretches = false;  // approach and rebound are reported (null where not fitted)
  std::optional<FittedStretch> approach, rebound;
  std::optional<std::string> missing, reference;
};

enum class BudgetPhase { approach, contact, rebound, collision };
const char* to_string(BudgetPhase p);

/// One phase of a collision's energy budget: the kinetic energies at both ends, each force's work and dissipation (by
/// model::ForceKind, in kAllForceKinds' order), and the closure ΔKE_spheres − Σ W.
struct EnergyPhase {
  BudgetPhase phase = BudgetPhase::approach;
  double t0_s = 0, t1_s = 0;
  std::array<double, 2> ke_spheres_J{}, ke_added_J{};  // at t0, t1
  std::array<double, model::kForceKinds> work_J{}, dissipated_J{}, dissipated_per_impact_energy{};
  double closure_J = 0, closure_per_impact_energy = 0;
};

/// One collision's energy budget (run/energy_budget.hpp): the unit, the largest kinetic energy of the approach, and
/// the phases approach, contact, rebound (after a separation) and the whole collision.
struct EnergyBudget {
  double impact_kinetic_energy_J = 0;
  std::vector<EnergyPhase> phases;
};

struct Bounce {
  int contact = 0;  // 1, 2, …
  double t_contact_s = 0;
  std::optional<double> t_separation_s;
  double impact_speed_at_delta_ss_m_s = 0;
  std::optional<double> e;  // by measure e_is
  EMeasure e_is = EMeasure::contact_ends;
  std::optional<double> impact_velocity_m_s, rebound_velocity_m_s, e_instant;
  std::optional<double> apex_gap_m, t_apex_s;  // the apex after the rebound
  std::optional<EnergyBudget> energy_budget;   // none where the run kept no work samples
  /// The distinct measures whose e differs from e by more than measure.disagreement, label (run/bounces.hpp
  /// measure_label) → e.
  std::vector<std::pair<std::string, double>> measures_disagree;
  std::vector<std::pair<EMeasure, MeasureResult>> e_measures;  // every named measure, in summary.json's order

  /// The named measure m (nullptr if it was not taken).
  const MeasureResult* measure(EMeasure m) const;
};

}  // namespace imcol::run
