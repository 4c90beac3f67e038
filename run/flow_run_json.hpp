// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// summary.json of `imcol flow` (without its `run` block) from a flow scene's typed result.
#include <nlohmann/json.hpp>

#include "run/flow_run_result.hpp"

namespace imcol {

nlohmann::ordered_json flow_summary_json(const FlowRunResult& r);

}  // namespace imcol
