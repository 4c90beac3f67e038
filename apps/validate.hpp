// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol validate seed`: the seed's Table 6.1 run by imcol (study/validate.hpp), printed with each model's agreement;
// writes DIR/validate_seed.csv and DIR/validate_seed.png (scripts/plot_validate_seed.py).
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "study/validate.hpp"

namespace imcol {

struct ValidateOptions : study::ValidateOptions {
  std::string out;  // default out/validate_seed (out/validate_seed_flow with --flow)
  bool plot = true;
};

/// Runs the validation set `what` (only "seed"); returns 0. The overrides (--set, --rtol, ...) apply to every run.
int cmd_validate(const std::string& what, const ValidateOptions& opt, const std::vector<Override>& overrides);

}  // namespace imcol
