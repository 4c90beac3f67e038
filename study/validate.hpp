// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The seed's Table 6.1 (data/reference/li_2010_table_6_1.csv) run by imcol with two gap laws, reduced-order and, with
// `flow`, also coupled (MODEL.md (6.10)); both St_B conventions (docs/model-notes.md, "Pairs"). Each run twice: at the
// printed V_Io, and at the approach speed that gives the printed St_B (study/validate_speed.hpp). Only the gap law
// differs between the models: the rest of the pair model is the scenes' (lagrangian added mass, K_H = 1, λ without
// the gap Reynolds number).
#include <cstddef>
#include <string>
#include <vector>

#include "core/choices.hpp"
#include "core/scene.hpp"
#include "study/executor.hpp"
#include "study/table_column.hpp"

namespace imcol::study {

/// One run of the seed's Table 6.1: its cells as printed (for the table and the CSV) and as numbers.
struct SeedRun {
  std::string run, pair, St_B, e, Re;
  double e_value = 0, St_B_value = 0;
};

/// Reads the table (data_dir()/reference/li_2010_table_6_1.csv); a malformed row is an InputError naming the file,
/// the line and the column.
std::vector<SeedRun> read_table_6_1();

/// A model the validation runs: its name (--models, the CSV's `model` column) and its gap law.
struct ValidateModel {
  std::string name;
  LubricationModel lubrication;
};

/// The models named (all if none); an unknown name is an InputError naming --models.
std::vector<ValidateModel> validate_models(const std::vector<std::string>& names);

/// The approach speed of a row: the printed V_Io, or the speed that gives the printed St_B.
enum class SpeedSet { V_Io, St_B };
const char* to_string(SpeedSet s);

/// What one run measured (NaN: not measured; the flow values NaN for a reduced-order run).
struct ValidateMeasures {
  double St = NAN, St_B_table_6_1 = NAN, St_B_eq_6_2 = NAN, e = NAN, e_instant = NAN, Re = NAN, group_velocity_m_s = NAN;
  double steps = NAN, wall_time_s = NAN;
  double flow_steps = NAN, flow_ms_per_step = NAN, cells_per_diameter = NAN, flow_dt_s = NAN;
};

/// One Table 6.1 run with one model at one speed: `run` the reported run (coupled with flow), `reduced` the
/// reduced-order one (the same run without flow).
struct ValidateRow {
  std::size_t seed = 0, model = 0;  // indices into the result's seeds and models
  SpeedSet set = SpeedSet::V_Io;
  double V = NAN;  // the approach speed, m/s
  ValidateMeasures run, reduced;
  std::string warning;  // the St_B row's speed not found, or no St_B at V_Io
};

/// A model's agreement with the seed's e in one set: runs within the tolerance, and the largest miss.
struct Agreement {
  int within = 0, runs = 0;
  double worst = 0;
  std::string worst_run;
  void add(const std::string& run, double e, double e_seed, double tol);
};

struct ValidateOptions {
  bool flow = false;
  std::vector<std::string> models;  // names; empty = all
  double tolerance = 0.05;          // |e - e_seed| counted as agreement
};

struct ValidateResult {
  bool flow = false;
  double tolerance = 0.05;
  std::vector<SeedRun> seeds;
  std::vector<ValidateModel> models;
  std::vector<ValidateRow> rows;  // the V_Io rows, then the St_B rows; in each, by seed run then model
  std::vector<Agreement> agreement, agreement_reduced;  // per set (V_Io, St_B) and model: set * models + model
  bool cancelled = false;  // the hooks stopped it: rows hold the runs that finished
  const SeedRun& seed_of(const ValidateRow& r) const { return seeds[r.seed]; }
  const ValidateModel& model_of(const ValidateRow& r) const { return models[r.model]; }
};

/// An InputError for a tolerance that is not a positive number, or a gap law among the overrides (the models set it).
void check_validate_options(const ValidateOptions& opt, const std::vector<Override>& overrides);

/// Runs every Table 6.1 run with every model on `ex` (the overrides apply to every run). The deciding process returns
/// the result; other ranks an empty one. A run that throws is rethrown on the deciding process.
ValidateResult validate_seed(const ValidateOptions& opt, const std::vector<Override>& overrides, const Executor& ex,
                             const Hooks& hooks = {});

/// A row's cell of validate_seed.csv: the row with the result it belongs to.
struct ValidateCell {
  const ValidateResult& result;
  const ValidateRow& row;
};
using ValidateColumn = RowColumn<ValidateCell>;

/// The table's columns, in order (with flow, the coupled run's and the reduced-order one's).
std::vector<ValidateColumn> validate_columns(bool flow);

}  // namespace imcol::study
