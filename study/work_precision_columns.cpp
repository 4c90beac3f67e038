// SPDX-License-Identifier: BSD-3-Clause
// The columns of a work-precision ladder's table (work_precision.csv; imcol.WorkPrecisionResult.table).
#include <algorithm>

#include "study/work_precision.hpp"

namespace imcol::study {

namespace work_precision_columns_impl {  // named: study/ is built in unity batches

using Row = WorkPrecisionRow;

WorkPrecisionColumn number(std::string name, double (*get)(const Row&)) { return {WorkPrecisionColumn::number, std::move(name), get, {}}; }
WorkPrecisionColumn integer(std::string name, long (*get)(const Row&)) {
  return {WorkPrecisionColumn::integer, std::move(name), [get](const Row& r) { return static_cast<double>(get(r)); }, {}};
}
WorkPrecisionColumn word(std::string name, std::string (*get)(const Row&)) { return {WorkPrecisionColumn::word, std::move(name), {}, get}; }

/// The message on one line and without commas.
std::string one_cell(const Row& r) {
  std::string msg = r.message;
  std::replace(msg.begin(), msg.end(), ',', ';');
  std::replace(msg.begin(), msg.end(), '\n', ' ');
  return msg;
}

}  // namespace work_precision_columns_impl

std::vector<WorkPrecisionColumn> work_precision_columns(const std::string& metric) {
  using namespace work_precision_columns_impl;
  return {word("integrator", [](const Row& r) { return r.cfg.integrator_name(); }),
          word("evaluator", [](const Row& r) { return r.cfg.evaluator_name(); }),
          number("rtol", [](const Row& r) { return r.rtol; }),
          number("atol", [](const Row& r) { return r.rtol; }),
          number("direct_step_s", [](const Row& r) { return r.direct_step; }),
          number("history_tolerance", [](const Row& r) { return r.history_tol; }),
          word("status", [](const Row& r) { return std::string(r.ok ? "ok" : "failed"); }),
          number(metric, [](const Row& r) { return r.e; }),
          number("err_" + metric, [](const Row& r) { return r.err_e; }),
          number("err_trajectory", [](const Row& r) { return r.err_traj; }),
          number("median_wall_ms", [](const Row& r) { return r.ms; }),
          integer("steps", [](const Row& r) { return r.steps; }),
          integer("rhs_evals", [](const Row& r) { return r.rhs; }),
          integer("lin_iters", [](const Row& r) { return r.lin_iters; }),
          word("message", one_cell)};
}

}  // namespace imcol::study
