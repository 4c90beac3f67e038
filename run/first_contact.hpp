// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The first contact of a run measured as the seed does (MODEL.md §3): impact and rebound velocities from
// least-squares lines over measure.window (m/s, fit_time), e (seed 6.1, fit_time), e_instant at measure.instant_gap, St (6.2) and
// Re at impact, the group velocity of a pair that moves on together; with the warnings that qualify them.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/collision_model.hpp"
#include "core/scene.hpp"
#include "run/bounces.hpp"
#include "run/watch.hpp"

namespace imcol::run {

struct FirstContact {
  std::optional<double> e, e_fit_raw, e_instant;
  std::optional<double> St, St_62, Re;
  std::optional<double> u_i1, u_i2, u_r1, u_r2;  // fitted, m/s
  std::optional<double> group_velocity, t_group;  // m/s, s
  double fit_window = 0;                          // s, as used (shortened to a short approach)
  bool separated = false;
  bool t_end_too_short = false;  // a longer solver.t_end would change e (never when the run ended at rest)
  bool stopped_by_t_end = false;  // the run ran to solver.t_end (did not end at rest or once e was measured)
  std::optional<std::string> e_missing;  // why e is undefined
  std::optional<std::string> e_by_measure;  // e_by_measure_line of the first contact
};

/// One plain line: e by each distinct named measure of a contact (measure_label), e's own first, and their spread.
std::string e_by_measure_line(const Scene& sc, const Bounce& b);

/// St in the reported convention (eq. 6.2 for a wall, half of it for a pair: seed Table 6.1) and St by (6.2).
std::pair<double, double> stokes_numbers(const model::CollisionModel& model, const Scene& sc, double u_rel);

/// Measures the first contact on the measures' track (Recorder::track()), with what the run's watchers saw.
FirstContact measure_first_contact(const model::CollisionModel& model, const Watch& watch, const Scene& sc, const Track& track,
                                   std::vector<std::string>& warnings);

/// `e` is the first contact's named measure measure.e (from measure_bounces); without a contact, the approach's e
/// (0 when the liquid stopped it). The other measures' e go to one plain line (e_by_measure), not to the warnings.
void choose_e(const Scene& sc, const std::vector<Bounce>& bounces, FirstContact& m, std::vector<std::string>& warnings);

/// Warnings for an e that cannot be trusted: above e_dry (energy created), or from loose tolerances.
void check_plausibility(const model::CollisionModel& model, const Scene& sc, const FirstContact& m,
                        std::vector<std::string>& warnings);

}  // namespace imcol::run
