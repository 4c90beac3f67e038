// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Every contact of a run and each named measure of e (docs/bounces.md): contact_ends (the default), the papers'
// yang_hunt_2006, joseph_2001, gondret_2002, and fit_time, fit_distance, at_gap, peak_rebound, instant; the apex
// between contacts. Velocities in m/s, gaps in m, times in s.
#include <array>
#include <string>
#include <vector>

#include "model/collision_model.hpp"
#include "model/force_work.hpp"
#include "core/scene.hpp"
#include "run/bounce.hpp"
#include "run/watch.hpp"

namespace imcol::run {

/// The samples the measures read: time, gap and U_rel (> 0 approaching); the spheres' positions and velocities
/// (z2, u2 zero for a wall).
struct Track {
  std::vector<double> t, gap, u;
  std::vector<double> z1, u1, z2, u2;
  /// The work of each force since t = 0 (model/force_work.hpp) and the kinetic energies of the spheres (Σ ½ m_p U²)
  /// and of the added mass (½ Uᵀ M_a U), J: the energy budget's samples (empty where the run kept none).
  std::vector<std::array<double, model::kForceKinds>> work;
  std::vector<double> ke_spheres, ke_added;
  /// Room for n samples (with the energy budget's when `energies`).
  void reserve(std::size_t n, bool energies);
  /// Time where the gap crosses g between samples i−1 and i (linear).
  double cross(std::size_t i, double g) const;
  /// U_rel where the gap crosses g between samples i−1 and i (linear).
  double u_at(std::size_t i, double g) const;
  std::size_t first_at_or_after(double t0) const;
};

/// The name under which measure `m` is compared and reported in measures_disagree: measures identical by construction
/// at the scene's settings share one, e.g. "fit_time/yang_hunt_2006" (measure.window = 10 ms), "fit_distance/joseph_2001"
/// (measure.fit_distance = 0.1), "peak_rebound/gondret_2002"; empty for the second name of such a pair.
std::string measure_label(const Scene& sc, EMeasure m);

/// One Bounce per contact, in order: times, velocities and e of the measure measure.e names, e_instant, apex,
/// every named measure, the energy budget and the measures that disagree (by measure_label: the distinct measures
/// whose e differs from e by more than measure.disagreement).
/// Appends a warning when a fit e was clipped to 0.
std::vector<Bounce> measure_bounces(const model::CollisionModel& model, const Watch& watch, const Scene& sc, const Track& tr,
                                       std::vector<std::string>& warnings);

}  // namespace imcol::run
