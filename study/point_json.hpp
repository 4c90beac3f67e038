// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A sweep point and a history sweep's cell as JSON (nlohmann's to_json/from_json, found by argument-dependent
// lookup): what they carry across the ranks of an MPI job (study/run_all.hpp, as CBOR). The run's summary is
// summary.json's object (run/summary_json.hpp), whose doubles read back to the same bits.
#include "run/summary_json.hpp"
#include "study/history_sweep.hpp"
#include "study/sweep_points.hpp"

namespace imcol::study {

void to_json(run::Json& j, const SweepPoint& p);
void from_json(const run::Json& j, SweepPoint& p);
void to_json(run::Json& j, const HistoryCell& c);
void from_json(const run::Json& j, HistoryCell& c);

}  // namespace imcol::study
