// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A run's summary as JSON, field for field (nlohmann's to_json/from_json, found by argument-dependent lookup): what a
// study's results carry across the ranks of an MPI job (study/run_all.hpp, as CBOR). Not summary.json (run/summary.hpp):
// every field, doubles as their exact bits (NaN and infinities too), enums as their numbers.
#include <nlohmann/json.hpp>

#include "run/run_summary.hpp"
#include "study/sweep_points.hpp"

namespace imcol::coupling {
void to_json(nlohmann::json& j, const FlowRunStats& s);
void from_json(const nlohmann::json& j, FlowRunStats& s);
}  // namespace imcol::coupling

namespace imcol {
void to_json(nlohmann::json& j, const FluidSpec& s);
void from_json(const nlohmann::json& j, FluidSpec& s);
void to_json(nlohmann::json& j, const SolverStats& s);
void from_json(const nlohmann::json& j, SolverStats& s);
void to_json(nlohmann::json& j, const SolverSummary& s);
void from_json(const nlohmann::json& j, SolverSummary& s);
void to_json(nlohmann::json& j, const FlowSummary& s);
void from_json(const nlohmann::json& j, FlowSummary& s);
void to_json(nlohmann::json& j, const ContactSummary& s);
void from_json(const nlohmann::json& j, ContactSummary& s);
void to_json(nlohmann::json& j, const BounceSummary& s);
void from_json(const nlohmann::json& j, BounceSummary& s);
void to_json(nlohmann::json& j, const RunSummary& s);
void from_json(const nlohmann::json& j, RunSummary& s);
}  // namespace imcol

namespace imcol::study {
void to_json(nlohmann::json& j, const SweepPoint& p);
void from_json(const nlohmann::json& j, SweepPoint& p);
}  // namespace imcol::study
