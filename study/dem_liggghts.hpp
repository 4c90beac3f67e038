// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// dem.json's `liggghts` block: LIGGGHTS's `hooke … viscous on` parameters (CriticalStokes, MaximumRestitution)
// fitted through the replay of its normal contact (study/dem_replay_fit.hpp), on the scene's materials, with the
// checks that go with them: the exp formula's parameters replayed, the restitution table replayed with a constant e
// per contact (docs/dem.md (a)), and the replay's e against the stiffness (Y*, characteristicVelocity) and step.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.hpp"
#include "study/dem_fit.hpp"
#include "study/dem_replay_fit.hpp"

namespace imcol::study {

/// The largest |e_replay − e| the replay fit may have to be said to reproduce imcol's e.
inline constexpr double kReplayTolerance = 0.03;

/// The scene's contact as LIGGGHTS's hooke model reads it (impactor and target or wall), at characteristicVelocity
/// `char_vel`; none without a target.
std::optional<HookeContact> hooke_contact(const Scene& s, double char_vel);

/// One point of the sweep as the block lists it.
struct ReplayPoint {
  double St = 0;
  double e = 0;
  bool used = false;               // e > 0: in the fit
  double e_formula = 0, e_fit = 0;  // replayed with the exp formula's parameters, with the fitted ones
};

/// e replayed at other stiffnesses: Y* and V_c scaled, the step either a fixed fraction of the contact time or the
/// base contact's Δt.
struct StiffnessCase {
  double Y_factor = 1, char_vel_factor = 1;
  bool same_dt = false;       // Δt of the base contact (else steps_per_contact of it)
  double steps_per_contact = 0;
  double max_change = 0;      // max |Δe| over the points against the base contact
};

struct LiggghtsExport {
  std::string error;  // why there is no fit (no liquid, no target, too few points); empty with one
  HookeContact contact;
  bool char_vel_from_points = true;  // V_c: the largest impact speed of the points (else 1 m/s: none measured)
  double mu = 0, k_n = 0, contact_time = 0;
  ReplayStep step;
  double E_i = 0, nu_i = 0, E_j = 0, nu_j = 0;
  std::vector<ReplayPoint> points;
  std::optional<ReplayFit> fit, fit_fixed;    // e_max free; e_max fixed to e_dry
  std::optional<ViscousRule> formula;         // the exp fit's St_c and e_dry as the rule's parameters
  double formula_rms = 0, formula_max = 0;    // their replay against the points used
  double table_max_difference = 0;            // constant-e replay of every table row with e > 0 against its e
  std::size_t table_rows = 0;
  std::vector<StiffnessCase> stiffness;
};

/// Fits the rule through the replay and runs the checks. `e_dry` fixes e_max in the second fit.
LiggghtsExport liggghts_export(const Scene& base, const std::vector<DemPoint>& pts, const DemFit& f, std::optional<double> e_dry);

/// The block as dem.json writes it.
nlohmann::ordered_json liggghts_json(const LiggghtsExport& x);

/// The terminal's words for it: the fitted parameters and the replay's residual.
std::string liggghts_text(const LiggghtsExport& x);

}  // namespace imcol::study
