// SPDX-License-Identifier: BSD-3-Clause
// The columns of the seed validation's table (validate_seed.csv; imcol.ValidateResult.table).
#include "study/validate.hpp"

namespace imcol::study {

namespace validate_columns_impl {  // named: study/ is built in unity batches

using Cell = ValidateCell;

ValidateColumn number(std::string name, double (*get)(const Cell&)) { return {ValidateColumn::number, std::move(name), get, {}}; }
ValidateColumn word(std::string name, std::string (*get)(const Cell&)) { return {ValidateColumn::word, std::move(name), {}, get}; }

const SeedRun& seed(const Cell& c) { return c.result.seed_of(c.row); }
double minus_seed(const Cell& c, double e) { return e - seed(c).e_value; }  // NaN without e

std::vector<ValidateColumn> reduced_order_columns() {
  return {number("e_reduced_order", [](const Cell& c) { return c.row.reduced.e; }),
          number("e_reduced_order_minus_e_seed", [](const Cell& c) { return minus_seed(c, c.row.reduced.e); }),
          number("St_B_table_6_1_reduced_order", [](const Cell& c) { return c.row.reduced.St_B_table_6_1; }),
          number("St_B_eq_6_2_reduced_order", [](const Cell& c) { return c.row.reduced.St_B_eq_6_2; }),
          number("wall_time_reduced_order_s", [](const Cell& c) { return c.row.reduced.wall_time_s; }),
          number("flow_steps", [](const Cell& c) { return c.row.run.flow_steps; }),
          number("flow_ms_per_step", [](const Cell& c) { return c.row.run.flow_ms_per_step; }),
          number("cells_per_diameter", [](const Cell& c) { return c.row.run.cells_per_diameter; }),
          number("flow_dt_s", [](const Cell& c) { return c.row.run.flow_dt_s; })};
}

}  // namespace validate_columns_impl

std::vector<ValidateColumn> validate_columns(bool flow) {
  using namespace validate_columns_impl;
  std::vector<ValidateColumn> cols = {
      word("run", [](const Cell& c) { return seed(c).run; }),
      word("pair", [](const Cell& c) { return seed(c).pair; }),
      word("model", [](const Cell& c) { return c.result.model_of(c.row).name; }),
      word("lubrication_model", [](const Cell& c) { return std::string(to_string(c.result.model_of(c.row).lubrication)); }),
      word("speed_set", [](const Cell& c) { return std::string(to_string(c.row.set)); }),
      number("V_m_s", [](const Cell& c) { return c.row.V; }),
      word("St_B_seed", [](const Cell& c) { return seed(c).St_B; }),
      word("e_seed", [](const Cell& c) { return seed(c).e; }),
      word("Re_seed", [](const Cell& c) { return seed(c).Re; }),
      number("St_B", [](const Cell& c) { return c.row.run.St; }),
      number("St_B_table_6_1", [](const Cell& c) { return c.row.run.St_B_table_6_1; }),
      number("St_B_eq_6_2", [](const Cell& c) { return c.row.run.St_B_eq_6_2; }),
      number("e", [](const Cell& c) { return c.row.run.e; }),
      number("e_minus_e_seed", [](const Cell& c) { return minus_seed(c, c.row.run.e); }),
      number("e_instant", [](const Cell& c) { return c.row.run.e_instant; }),
      number("Re", [](const Cell& c) { return c.row.run.Re; }),
      number("group_velocity_m_s", [](const Cell& c) { return c.row.run.group_velocity_m_s; }),
      number("steps", [](const Cell& c) { return c.row.run.steps; }),
      number("wall_time_s", [](const Cell& c) { return c.row.run.wall_time_s; })};
  if (flow)
    for (auto& c : reduced_order_columns()) cols.push_back(std::move(c));
  return cols;
}

}  // namespace imcol::study
