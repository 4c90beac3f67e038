// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `imcol validate seed`: the seed's Table 6.1 (data/reference/li_2010_table_6_1.csv) run by imcol with two gap laws,
// reduced-order and with --flow also coupled (MODEL.md (6.10)); both St_B conventions (docs/model-notes.md, "Pairs").
// Each run twice: at the printed V_Io, and at the approach speed that gives the printed St_B (apps/validate_speed.hpp).
// Writes DIR/validate_seed.csv and DIR/validate_seed.png (scripts/plot_validate_seed.py).
#include <string>
#include <vector>

#include "core/choices.hpp"
#include "core/scene.hpp"

namespace imcol {

/// One run of the seed's Table 6.1: its cells as printed (for the table and the CSV) and as numbers.
struct SeedRun {
  std::string run, pair, St_B, e, Re;
  double e_value = 0, St_B_value = 0;
};

/// Reads the table (data_dir()/reference/li_2010_table_6_1.csv); a malformed row is an InputError naming the file,
/// the line and the column.
std::vector<SeedRun> read_table_6_1();

/// A model `imcol validate seed` runs: its name (in --models and the CSV's `model` column) and its gap law.
struct ValidateModel {
  std::string name;
  LubricationModel lubrication;
};

struct ValidateOptions {
  std::string out;                  // default out/validate_seed (out/validate_seed_flow with --flow)
  bool flow = false, plot = true;
  std::vector<std::string> models;  // names; empty = all
  double tolerance = 0.05;          // |e - e_seed| counted as agreement in the closing lines
};

/// The models named (all if none); an unknown name is an InputError naming --models.
std::vector<ValidateModel> validate_models(const std::vector<std::string>& names);

/// Runs the validation set `what` (only "seed"); returns 0. The overrides (--set, --rtol, ...) apply to every run.
int cmd_validate(const std::string& what, const ValidateOptions& opt, const std::vector<Override>& overrides);

}  // namespace imcol
