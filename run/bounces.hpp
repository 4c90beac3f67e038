#pragma once
// Every contact of a run and each named measure of e (docs/bounces.md): fit_time, fit_distance, at_gap,
// peak_rebound, instant; the apex between contacts. Velocities in m/s, gaps in m, times in s.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "contact/collision_model.hpp"
#include "core/scene.hpp"

namespace imcol::run {

/// The samples the measures read: time, gap and U_rel (> 0 approaching).
struct Track {
  std::vector<double> t, gap, u;
  /// Time where the gap crosses g between samples i−1 and i (linear).
  double cross(std::size_t i, double g) const;
  /// U_rel where the gap crosses g between samples i−1 and i (linear).
  double u_at(std::size_t i, double g) const;
  std::size_t first_at_or_after(double t0) const;
};

/// The track of a trajectory whose columns t, gap and U_rel are at indices 0, 3 and `u_rel_column`.
Track track_from_rows(const std::vector<std::vector<double>>& rows, std::size_t u_rel_column);

/// One object per contact, in order: times, velocities, e (fit_time), e_instant, apex and `e_measures`.
/// Appends a warning when a fit e was clipped to 0.
nlohmann::ordered_json measure_bounces(const contact::CollisionModel& model, const Scene& sc, const Track& tr,
                                       std::vector<std::string>& warnings);

}  // namespace imcol::run
