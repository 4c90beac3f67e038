// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON edge of a run's contacts (run/bounce.hpp): summary.json's `bounces` entries and `energy_budget`, written
// from the types and read back (to_json/from_json, found by nlohmann through argument-dependent lookup). Written,
// read and written again gives the same bytes.
#include "run/bounce.hpp"
#include "run/json_util.hpp"

namespace imcol::run {

void to_json(Json& j, const FittedPosition& p);
void from_json(const Json& j, FittedPosition& p);
void to_json(Json& j, const FittedStretch& s);
void from_json(const Json& j, FittedStretch& s);
void to_json(Json& j, const MeasureResult& m);
void from_json(const Json& j, MeasureResult& m);
void to_json(Json& j, const EnergyPhase& p);
void from_json(const Json& j, EnergyPhase& p);
void to_json(Json& j, const EnergyBudget& b);
void from_json(const Json& j, EnergyBudget& b);
void to_json(Json& j, const Bounce& b);
void from_json(const Json& j, Bounce& b);

/// A stretch as summary.json writes it: null when none.
Json stretch_or_null(const std::optional<FittedStretch>& s);

}  // namespace imcol::run
