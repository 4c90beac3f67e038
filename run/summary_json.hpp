// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// summary.json of a collision run: the JSON edge of RunSummary (run/run_summary.hpp). Written from the types alone,
// and read back into them (to_json/from_json, found by nlohmann through argument-dependent lookup: the bytes a run's
// summary crosses MPI ranks as). Written, read and written again gives the same bytes.
#include "run/bounce_json.hpp"
#include "run/json_util.hpp"
#include "run/run_summary.hpp"

namespace imcol {

void to_json(run::Json& j, const RunSummary& s);
void from_json(const run::Json& j, RunSummary& s);

void to_json(run::Json& j, const ContactSummary& c);
void from_json(const run::Json& j, ContactSummary& c);
void to_json(run::Json& j, const FlowSummary& f);
void from_json(const run::Json& j, FlowSummary& f);
void to_json(run::Json& j, const SolverSummary& s);
void from_json(const run::Json& j, SolverSummary& s);
void to_json(run::Json& j, const FluidSpec& f);
void from_json(const run::Json& j, FluidSpec& f);
void to_json(run::Json& j, const EventSummary& e);
void from_json(const run::Json& j, EventSummary& e);

/// The effects as summary.json lists them (names), and back (an unknown name: std::invalid_argument).
run::Json effects_to_json(const std::vector<Effect>& effects);
std::vector<Effect> effects_of(const run::Json& names);

}  // namespace imcol
