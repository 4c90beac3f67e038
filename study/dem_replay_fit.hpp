// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// LIGGGHTS's `viscous on` parameters (CriticalStokes St_c, MaximumRestitution e_max) fitted through the replay of its
// hooke normal contact (study/dem_replay.hpp): least squares in e over the samples, e(St) being the replay's at
// the impact speed of each St. Search on St_c in [1e-3 St_min, 2 St_max] (log scale) and e_max in [0.01, 1]: an
// 11 × 11 grid, then NLopt's BOBYQA (calibrate/local_search.hpp) from its best point. e_max may instead be fixed.
#include <optional>
#include <vector>

#include "study/dem_replay.hpp"

namespace imcol::study {

struct ReplaySample {
  double St = 0;  // the DEM convention, > 0
  double e = 0;   // > 0
};

struct ReplayFit {
  ViscousRule rule;             // FluidViscosity as given, St_c and e_max fitted (e_max fixed when asked)
  bool e_max_free = true;
  double rms_residual = 0, max_residual = 0, max_residual_St = 0;  // in e, e_replay − e
  std::vector<double> e_replay;  // at the samples
  int evaluations = 0;
};

/// The replay's e at each St (the impact speed from St, m* and r*).
std::vector<double> replayed_restitution(const HookeContact& c, const ViscousRule& rule, const std::vector<double>& St,
                                         const ReplayStep& step = {});

/// The fewest samples a fit takes: 3 with e_max free, 2 with it fixed.
std::size_t min_replay_samples(bool e_max_free);

/// Fits St_c (and e_max unless fixed) to the samples; throws std::invalid_argument with too few samples or a
/// sample with St or e not positive.
ReplayFit fit_viscous_rule(const std::vector<ReplaySample>& samples, const HookeContact& c, double mu,
                           std::optional<double> e_max_fixed = std::nullopt, const ReplayStep& step = {});

}  // namespace imcol::study
