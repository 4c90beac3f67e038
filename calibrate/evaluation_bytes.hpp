// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A work item's evaluations as bytes (JSON text), so that they can move between MPI ranks: doubles written with 17
// digits read back the same; a NaN or infinity is written as null and read back as NaN (e_sim) or +inf (objective).
#include <string>
#include <utility>
#include <vector>

#include "calibrate/objective.hpp"

namespace imcol::calib {

using ValuedEvaluation = std::pair<std::vector<double>, Evaluation>;  // parameter values, their evaluation

std::string evaluations_to_bytes(const std::vector<ValuedEvaluation>& evals);
/// The evaluations that evaluations_to_bytes wrote. std::invalid_argument, saying which evaluation and field, for bytes
/// it could not have written: not a non-empty JSON list, a field missing or of another type, parameter values that
/// are not finite, an evaluation that succeeded without a finite objective and rms >= 0.
std::vector<ValuedEvaluation> evaluations_from_bytes(const std::string& bytes);

/// Points of the unit cube (the stages' inputs) as bytes and back.
std::string points_to_bytes(const std::vector<std::vector<double>>& points);
std::vector<std::vector<double>> points_from_bytes(const std::string& bytes);

}  // namespace imcol::calib
