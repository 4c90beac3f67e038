// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A sweep's e against St in the shape a soft-sphere DEM code reads (docs/dem.md): each point's St in the DEM
// convention and the fits of e = e_dry f(St_c/St) (run/restitution_fit.hpp), exp and linear, e_dry fixed and free.
// St is m* U / (6 π μ a*²) (the convention of LIGGGHTS's viscous restitution): the summary's St for a wall,
// St_B_eq_6_2 for a pair (twice the summary's St there).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run/restitution_fit.hpp"
#include "study/sweep.hpp"
#include "study/table.hpp"

namespace imcol::study {

/// One sweep point as the DEM fit reads it.
struct DemPoint {
  double value = 0;      // of the varied quantity, SI
  bool ok = false;       // the run finished (sweep.csv status ok)
  std::string e_status;  // measured | measures_disagree | not_measured (empty for a failed run)
  std::optional<double> impact_speed_m_s, St, St_B_eq_6_2, e;
};

/// The points of a sweep as the fit reads them.
std::vector<DemPoint> dem_points(const SweepResult& sweep);

/// The largest |residual| in e a fit may have to be said to fit the data (dem.json `supported`).
inline constexpr double kDemFitTolerance = 0.05;

/// The St convention in words (dem.json St_convention).
extern const char* const kDemStConvention;

/// The St a DEM code computes: the summary's St for a wall, St_B_eq_6_2 for a pair.
std::optional<double> dem_St(const DemPoint& p, bool pair);

/// The fits and what the points held.
struct DemFit {
  bool pair = false;
  std::vector<run::RestitutionFit> fits;  // exp (e_dry fixed, free), linear (fixed, free); those that failed left out
  int best = -1;                          // the smallest rms residual with e_dry free (fixed if none), e_dry <= 1
  int exp = -1;                           // the exponential formula's fit (e_dry free if <= 1); LIGGGHTS's rule differs (dem_liggghts.hpp)
  std::string fit_error;                  // why a fit is missing (the first failure; a scene without a liquid)
  std::size_t total = 0, used = 0, no_rebound = 0, without_e = 0, without_St = 0;
  std::optional<double> St_no_rebound_max;
};

/// Fits both forms to the points, e_dry fixed to `e_dry` (when given) and free. Without a liquid (`liquid` false)
/// St is infinite: no fit, and fit_error says why.
DemFit fit_dem(const std::vector<DemPoint>& pts, std::optional<double> e_dry, bool liquid, bool pair);

/// One fit as dem.json lists it.
nlohmann::ordered_json dem_fit_json(const run::RestitutionFit& f, bool pair);

/// dem.csv's table: point, the varied quantity's column, impact_speed_m_s, St, St_B_eq_6_2 (a pair), e,
/// e_over_e_dry, status, e_status, used_in_fit.
Table dem_table(const std::vector<DemPoint>& pts, const std::string& column, std::optional<double> e_dry, bool pair);

}  // namespace imcol::study
