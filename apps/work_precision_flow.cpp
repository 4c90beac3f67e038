// SPDX-License-Identifier: BSD-3-Clause
#include "apps/work_precision_flow.hpp"

#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "apps/cluster.hpp"
#include "apps/format.hpp"
#include "apps/rank_inputs.hpp"
#include "apps/cluster.hpp"
#include "run/summary_json.hpp"
#include "core/report.hpp"

namespace imcol {

namespace {

void print_flow_ladder_heading(const std::string& scene) {
  std::cout << "work-precision of the coupled model, " << scene << " (error against the finest rung of each ladder)\n";
  std::cout << std::left << std::setw(6) << "ladder" << std::right << std::setw(7) << "cells" << std::setw(7) << "cfl"
            << std::setw(11) << "dt s" << std::setw(9) << "e" << std::setw(11) << "|e-e_ref|" << std::setw(9) << "e_inst"
            << std::setw(9) << "wall s" << std::setw(7) << "steps" << std::setw(10) << "ms/step" << "\n";
}

void print_flow_ladder_row(const study::FlowLadderRow& r) {
  std::cout << std::left << std::setw(6) << r.ladder << std::right << std::setw(7) << r.cells << std::setw(7) << r.cfl
            << std::setw(11) << sci(r.dt, 2) << std::setw(9) << fixed(r.e, 4) << std::setw(11)
            << (r.reference ? std::string("ref") : sci(r.err, 2)) << std::setw(9) << fixed(r.e_instant, 4)
            << std::setw(9) << fixed(r.wall_time_s, 2) << std::setw(7) << r.steps
            << std::setw(10) << fixed(r.ms_per_step, 1) << "\n";
}

std::string flow_ladder_csv(const study::FlowLadderResult& res) {
  std::ostringstream csv;
  csv << "ladder,cells_per_diameter,cfl,dt_s,e,e_error_vs_finest,e_instant,wall_time_s,flow_steps,ms_per_flow_step,krylov_per_step\n";
  for (const auto& r : res.rows)
    csv << r.ladder << "," << r.cells << "," << csv_number(r.cfl) << "," << csv_number(r.dt) << "," << csv_number(r.e) << ","
        << csv_number(r.err) << "," << csv_number(r.e_instant) << "," << csv_number(r.wall_time_s) << "," << r.steps << ","
        << csv_number(r.ms_per_step) << "," << csv_number(r.krylov) << "\n";
  return csv.str();
}

nlohmann::ordered_json flow_ladder_json(const study::FlowLadderResult& res) {
  nlohmann::ordered_json js = {{"scene", res.scene}, {"reference", "the finest rung of each ladder"}, {"rungs", nlohmann::ordered_json::array()}};
  for (const auto& r : res.rows)
    js["rungs"].push_back({{"ladder", r.ladder}, {"cells_per_diameter", r.cells}, {"cfl", r.cfl}, {"dt_s", r.dt}, {"e", r.e},
                           {"e_error_vs_finest", r.err}, {"e_instant", r.e_instant}, {"wall_time_s", r.wall_time_s},
                           {"flow", r.flow ? run::Json(*r.flow) : run::Json(nullptr)}});
  if (res.ranks > 1) js["ranks"] = res.ranks;
  return js;
}

}  // namespace

int work_precision_flow(const Scene& base, const std::vector<Override>& overrides, const FlowLadderOptions& opt, const std::filesystem::path& fallback) {
  study::check_flow_ladder(base, opt);
  const std::vector<study::FlowRung> rungs = study::flow_rungs(base, opt);
  auto notice = [&](std::size_t i, int rank) {  // on stderr, as each rung starts (one rank) or arrives (several)
    std::cerr << "  " << rungs[i].ladder << ": " << rungs[i].cells << " cells/D, cfl " << rungs[i].cfl << " ..."
              << (rank < 0 ? std::string() : " (on rank " + std::to_string(rank) + ")") << "\n";
  };
  auto load = [&](const std::vector<Override>& keys) {
    auto ov = overrides;
    ov.insert(ov.end(), keys.begin(), keys.end());
    return load_scene(base.path, ov);
  };
  if (const int differ = cluster::agree(flow_ladder_inputs(base, opt))) return differ;  // ranks on other inputs: refused
  std::optional<OutputUnit> unit;
  if (const int refused = cluster::on_rank0([&] { unit.emplace(opt.out, fallback, base.path); })) return refused;
  const study::Executor ex = cluster_executor(1);  // one run at a time per rank: wall times not shared
  const study::FlowLadderResult res = study::flow_ladder(base, load, opt, ex, {}, notice);
  if (!ex.deciding()) return 0;
  print_flow_ladder_heading(res.scene);
  for (const auto& r : res.rows) print_flow_ladder_row(r);
  nlohmann::ordered_json js = flow_ladder_json(res);
  js["run"] = unit->run();
  write_file_atomic(unit->dir() / "work_precision_flow.csv", flow_ladder_csv(res));
  write_file_atomic(unit->dir() / "work_precision_flow.json", js.dump(2) + "\n");
  unit->commit();
  std::cout << "wrote " << (unit->target() / "work_precision_flow.csv").string() << " and .json\n";
  return 0;
}

}  // namespace imcol
