// SPDX-License-Identifier: BSD-3-Clause
#include "apps/work_precision.hpp"
#include "apps/work_precision_flow.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "apps/cluster.hpp"
#include "apps/format.hpp"
#include "apps/plot.hpp"
#include "apps/rank_inputs.hpp"
#include "apps/cluster.hpp"
#include "run/summary_json.hpp"
#include "core/errors.hpp"
#include "core/work_scope.hpp"
#include "core/report.hpp"

namespace imcol {

namespace fs = std::filesystem;

namespace {

using study::WorkPrecisionResult;
using study::WorkPrecisionRow;

/// The table of every rung against the reference.
void print_table(const WorkPrecisionResult& res) {
  const std::string& metric = res.metric;
  std::cout << "scene " << res.scene << ": work-precision, median of " << res.repeat << " runs per setting (atol = rtol"
            << (res.history ? "; soe fit tolerance = rtol within [1e-10, 1e-3]" : "") << ")\n";
  std::cout << "reference: cvode dense, rtol = atol = " << res.ref_rtol
            << (res.history ? ", soe fit tolerance " + sci(res.ref_history_tol, 0) : std::string()) << ": " << metric << " = "
            << std::setprecision(12) << res.value << "; its uncertainty ~ " << sci(res.uncertainty) << "\n";
  std::cout << "trajectory error: max over output times of |d gap|/D and |d u|/" << sci(res.u_scale, 3) << " m/s\n";
  for (const auto& s : res.skipped) std::cout << "skipped " << s << "\n";
  std::cout << std::left << std::setw(22) << "integrator / history" << std::right << std::setw(9) << "rtol" << std::setw(11)
            << "direct dt" << std::setw(16) << metric << std::setw(10) << "err " + metric << std::setw(10) << "err traj"
            << std::setw(11) << "median ms" << std::setw(8) << "steps" << std::setw(8) << "rhs" << "\n";
  for (const auto& p : res.rows) {
    std::cout << std::left << std::setw(22) << p.cfg.label() << std::right << std::setw(9) << sci(p.rtol, 0) << std::setw(11)
              << sci(p.direct_step, 1);
    if (p.ok)
      std::cout << std::setw(16) << std::fixed << std::setprecision(11) << p.e << std::setw(10) << sci(p.err_e, 1) << std::setw(10)
                << sci(p.err_traj, 1) << std::setw(11) << std::setprecision(3) << p.ms << std::setw(8) << p.steps << std::setw(8)
                << p.rhs << "\n";
    else
      std::cout << "  " << p.message << "\n";
  }
}

nlohmann::ordered_json or_null(const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nullptr; }

/// The observed orders, printed and as the JSON file's block.
nlohmann::ordered_json observed_orders(const WorkPrecisionResult& res) {
  nlohmann::ordered_json orders = nlohmann::ordered_json::object();
  std::cout << "observed order (fits over errors above " << sci(res.order_floor, 0)
            << "): err ~ rtol^a (tolerance proportionality), err ~ steps^-p\n";
  for (const auto& o : res.orders) {
    std::cout << "  " << std::left << std::setw(22) << o.config << std::right << " err ~ " << o.vs << "^"
              << (o.exponent ? fixed(*o.exponent, 2) : std::string("n/a")) << "   p = "
              << (o.order_in_steps ? fixed(*o.order_in_steps, 2) : std::string("n/a")) << "   (" << o.points << " points)\n";
    orders[o.config] = {{"vs", o.vs}, {"exponent", or_null(o.exponent)}, {"order_in_steps", or_null(o.order_in_steps)}, {"points", o.points}};
  }
  return orders;
}

/// The cheapest settings, printed and as the JSON file's block.
nlohmann::ordered_json cheapest_settings(const WorkPrecisionResult& res) {
  nlohmann::ordered_json cheapest = nlohmann::ordered_json::object();
  std::cout << "cheapest setting that reaches an error in " << res.metric << " (and keeps it at every tighter rung):\n";
  for (const auto& c : res.cheapest) {
    std::cout << "  " << sci(c.target, 0) << ": ";
    if (!c.row) {
      std::cout << "not reached\n";
      cheapest[sci(c.target, 0)] = nullptr;
      continue;
    }
    const WorkPrecisionRow& best = res.rows[*c.row];
    const bool direct = !std::isnan(best.direct_step);
    std::cout << best.cfg.label() << ", rtol " << sci(best.rtol, 0) << (direct ? ", direct_step " + sci(best.direct_step) : "")
              << " (" << std::fixed << std::setprecision(3) << best.ms << " ms, error " << sci(best.err_e, 1) << ")\n";
    cheapest[sci(c.target, 0)] = {{"config", best.cfg.label()}, {"rtol", best.rtol},
                                  {"direct_step_s", direct ? nlohmann::ordered_json(best.direct_step) : nlohmann::ordered_json(nullptr)},
                                  {"median_ms", best.ms}, {"error", best.err_e}};
  }
  return cheapest;
}

/// work_precision.csv: the columns of study::work_precision_columns.
std::string rows_csv(const WorkPrecisionResult& res) {
  const auto columns = study::work_precision_columns(res.metric);
  std::ostringstream csv;
  for (std::size_t c = 0; c < columns.size(); ++c) csv << (c ? "," : "") << columns[c].name;
  csv << "\n";
  for (const auto& p : res.rows) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const auto& col = columns[c];
      csv << (c ? "," : "");
      if (col.kind == study::WorkPrecisionColumn::word) csv << col.text(p);
      else if (col.kind == study::WorkPrecisionColumn::integer) csv << static_cast<long>(col.value(p));
      else csv << csv_number(col.value(p));
    }
    csv << "\n";
  }
  return csv.str();
}

/// work_precision.json but its `run` block.
nlohmann::ordered_json result_json(const WorkPrecisionResult& res, nlohmann::ordered_json orders, nlohmann::ordered_json cheapest) {
  nlohmann::ordered_json j;
  j["scene"] = res.scene;
  j["metric"] = res.metric;
  j["reference"] = {{"integrator", res.reference.integrator_name()}, {"evaluator", res.reference.evaluator_name()}, {"rtol", res.ref_rtol},
                    {"atol", res.ref_rtol}, {"history_tolerance", res.history ? nlohmann::ordered_json(res.ref_history_tol) : nullptr},
                    {"value", res.value}, {"uncertainty", res.uncertainty}, {"wall_time_s", res.wall_time_s},
                    {"solver", run::Json(res.solver)}};  // the reference run's solver block as in its summary.json
  j["trajectory_velocity_scale_m_s"] = res.u_scale;
  j["repeat"] = res.repeat;
  j["skipped"] = res.skipped;
  j["observed_order"] = std::move(orders);
  j["cheapest"] = std::move(cheapest);
  j["effects"] = effects_to_json(res.effects);
  if (res.runs_by_rank.size() > 1) {
    j["ranks"] = res.runs_by_rank.size();
    j["runs_by_rank"] = res.runs_by_rank;
  }
  return j;
}

/// The progress line of a run (stderr): the reference's, or a rung's; `rank` >= 0 where it ran on another rank.
void progress_line(const study::WorkPrecisionPlan& plan, std::size_t i, int rank, bool last_of_several) {
  const std::string where = rank < 0 ? "" : (last_of_several ? " (its last run on rank " : " (on rank ") + std::to_string(rank) + ")";
  if (i == 0) {
    std::cerr << "reference run (cvode dense, rtol = atol = " << plan.opt.ref_rtol << ")" << where << "\n";
    return;
  }
  const study::Rung& g = plan.rung(i);
  std::cerr << "  " << g.cfg.label() << "  rtol " << sci(g.rtol, 0) << (std::isnan(g.direct_step) ? "" : "  direct_step " + sci(g.direct_step))
            << where << "\n";
}

/// The plan of a collision scene: the scene's own solver options are refused (the ladder sets them).
study::WorkPrecisionPlan collision_plan(const Scene& base, const WorkPrecisionOptions& opt) {
  if (!opt.ladder_options.empty())
    throw InputError("command line", opt.ladder_options.front(),
                     "work-precision sets rtol = atol along --rtols and the integrator along --integrators: give them there");
  return study::plan_work_precision(base, opt);
}

/// Prints the result and writes its files into `unit`.
void write_result(const WorkPrecisionResult& res, const WorkPrecisionOptions& opt, OutputUnit& unit) {
  print_table(res);
  const nlohmann::ordered_json orders = observed_orders(res);
  const nlohmann::ordered_json cheapest = cheapest_settings(res);
  nlohmann::ordered_json j = result_json(res, orders, cheapest);
  j["run"] = unit.run();
  write_file_atomic(unit.dir() / "work_precision.csv", rows_csv(res));
  write_file_atomic(unit.dir() / "work_precision.json", j.dump(2) + "\n");
  if (opt.plot) run_plot_script("plot_work_precision.py", unit, "work_precision.png");
  unit.commit();
  std::cout << "wrote " << (unit.target() / "work_precision.csv").string() << " and " << (unit.target() / "work_precision.json").string() << "\n";
}

}  // namespace

int work_precision(const std::string& scene_path, const std::vector<Override>& overrides, const WorkPrecisionOptions& opt) {
  study::check_work_precision_options(opt);
  const Scene base = load_scene(scene_path, overrides);
  const fs::path fallback = fs::path("out") / (base.name + "-work_precision");
  if (base.has(Effect::flow)) {  // a coupled scene: the ladder is the grid and the flow step
    FlowLadderOptions fo;
    fo.out = opt.out;
    return work_precision_flow(base, overrides, fo, fallback);
  }
  const study::WorkPrecisionPlan plan = collision_plan(base, opt);
  // Under mpirun, ranks > 0 run what rank 0 hands them (docs/cluster.md); rank 0 alone writes and prints.
  if (const int differ = cluster::agree(work_precision_inputs(plan.base, opt))) return differ;  // ranks on other inputs: refused
  std::optional<OutputUnit> unit;
  if (const int refused = cluster::on_rank0([&] { unit.emplace(opt.out, fallback, base.path); })) return refused;
  const study::Executor ex = cluster_executor(1);  // one run at a time per rank: wall times not shared with another run
  auto notice = [&](std::size_t i, int rank) { progress_line(plan, i, rank, i > 0 && opt.repeat > 1); };
  const WorkPrecisionResult res = study::work_precision(plan, ex, {}, notice);
  this_thread_work().stop.throw_if_requested();  // Ctrl-C: nothing printed or kept of a stopped study
  if (!ex.deciding()) return 0;
  write_result(res, opt, *unit);
  return 0;
}

}  // namespace imcol
