// SPDX-License-Identifier: BSD-3-Clause
#include "apps/work_precision_flow.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "apps/cluster.hpp"
#include "apps/format.hpp"
#include "apps/rank_inputs.hpp"
#include "apps/run_failure.hpp"
#include "run/json_util.hpp"
#include "run/simulate.hpp"
#include "run/summary_json.hpp"
#include "run/summary.hpp"
#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "core/report.hpp"
#include "coupling/step_rule.hpp"

namespace imcol {

namespace {

struct FlowRung {
  std::string ladder;
  int cells;
  double cfl;
};

/// What a rung's run tells rank 0 (as JSON, whose numbers read back to the same doubles, when it ran on another
/// rank): e, e_instant, the wall time and the flow solver's block; or what it threw.
struct FlowRungResult {
  double e = NAN, e_instant = NAN, wall_time_s = NAN, dt = NAN, ms_per_step = NAN, krylov = NAN;
  long steps = 0;
  nlohmann::ordered_json flow;  // summary.json's flow block
  RunFailure failure;
};

double num(const nlohmann::ordered_json& v) { return v.is_null() ? NAN : v.get<double>(); }

std::string encode_flow_rung(const FlowRungResult& r) {
  const nlohmann::ordered_json j = {{"e", r.e}, {"e_instant", r.e_instant}, {"wall_time_s", r.wall_time_s}, {"dt", r.dt},
                                    {"ms_per_step", r.ms_per_step}, {"krylov", r.krylov}, {"steps", r.steps}, {"flow", r.flow},
                                    {"failure", r.failure.kind}, {"what", r.failure.what}, {"where", r.failure.where},
                                    {"key", r.failure.key}, {"problem", r.failure.problem}};
  return j.dump();  // NaN becomes null
}

FlowRungResult decode_flow_rung(const std::string& bytes) {
  const auto j = nlohmann::ordered_json::parse(bytes);
  FlowRungResult r;
  r.e = num(j["e"]), r.e_instant = num(j["e_instant"]), r.wall_time_s = num(j["wall_time_s"]), r.dt = num(j["dt"]);
  r.ms_per_step = num(j["ms_per_step"]), r.krylov = num(j["krylov"]);
  r.steps = j["steps"].get<long>();
  r.flow = j["flow"];
  r.failure.kind = j["failure"].get<int>();
  r.failure.what = j["what"], r.failure.where = j["where"], r.failure.key = j["key"], r.failure.problem = j["problem"];
  return r;
}

FlowRungResult run_flow_rung(const Scene& base, const std::vector<Override>& overrides, const FlowRung& g) {
  FlowRungResult out;
  try {
    auto ov = overrides;
    ov.push_back({"flow.cells_per_diameter", std::to_string(g.cells)});
    ov.push_back({"flow.cfl", toml_float(g.cfl)});
    Scene sc = load_scene(base.path, ov);
    sc.flow.fields = false;
    const RunResult run = simulate(sc);
    const auto& s = run.summary;
    const FlowSummary& f = s.flow.value();
    out.e = s.e.value_or(NAN), out.e_instant = s.e_instant.value_or(NAN), out.wall_time_s = s.wall_time_s;
    out.dt = f.stats.dt, out.ms_per_step = f.ms_per_step, out.krylov = f.krylov_iterations_per_step;
    out.steps = static_cast<long>(f.stats.steps);
    out.flow = run::Json(f);
  } catch (const std::exception&) {
    out.failure = RunFailure::current();
  }
  return out;
}

}  // namespace

int work_precision_flow(const Scene& base, const std::vector<Override>& overrides, const FlowLadderOptions& opt, const std::filesystem::path& fallback) {
  if (opt.cells.size() < 2 || opt.cfls.size() < 2) throw InputError("work-precision", "ladder", "each ladder needs two rungs or more");
  for (int c : opt.cells)
    if (c < 4 || c > 512) throw InputError("--cells", "cells", "cells per diameter must lie in [4, 512]");
  for (double c : opt.cfls)
    if (!(c > 0 && c <= 1)) throw InputError("--cfls", "cfls", "each cfl must lie in (0, 1]");
  if (base.flow.dt > 0) throw InputError(base.path, "flow.dt", "the step ladder varies flow.cfl: remove flow.dt from the scene");
  std::vector<FlowRung> rungs;
  double u_ref = 0;  // the grid ladder keeps the scene's cfl, or the default cfl(Re) of coupling/step_rule.hpp
  for (const auto& sp : base.spheres) u_ref = std::max(u_ref, std::abs(sp.velocity));
  for (int c : opt.cells) {
    Scene at = base;
    at.flow.cells_per_diameter = c;
    rungs.push_back({"grid", c, base.flow.cfl > 0 ? base.flow.cfl : coupling::flow_step(at, 1.0, u_ref).cfl});
  }
  for (double f : opt.cfls) rungs.push_back({"step", base.flow.cells_per_diameter, f});

  // The rungs, spread over the MPI job's ranks (docs/cluster.md) or run one after the other; rank 0 alone writes.
  const cluster::World w = cluster::world();
  auto progress = [&](const FlowRung& g, const std::string& where) {
    std::cerr << "  " << g.ladder << ": " << g.cells << " cells/D, cfl " << g.cfl << " ..." << where << "\n";
  };
  std::vector<std::exception_ptr> thrown(rungs.size());  // this process's runs: rank 0 rethrows the exception itself
  auto work = [&](std::size_t i) {
    if (w.size == 1) progress(rungs[i], "");
    FlowRungResult r = run_flow_rung(base, overrides, rungs[i]);
    thrown[i] = r.failure.thrown;
    return encode_flow_rung(r);
  };
  if (const int differ = cluster::agree(flow_ladder_inputs(base, opt))) return differ;  // ranks on other inputs: refused
  std::optional<OutputUnit> unit;
  if (const int refused = cluster::on_rank0([&] { unit.emplace(opt.out, fallback, base.path); })) return refused;
  if (w.rank > 0) {
    cluster::run_distributed(rungs.size(), 1, work, {});
    return 0;
  }
  std::vector<FlowRungResult> results(rungs.size());
  std::size_t stop = rungs.size();  // a failed rung ends the command
  cluster::run_distributed(rungs.size(), 1, work, [&](std::size_t i, std::string bytes, int rank) {
    results[i] = decode_flow_rung(bytes);
    if (w.size > 1) progress(rungs[i], " (on rank " + std::to_string(rank) + ")");
    if (results[i].failure.kind == RunFailure::none) return true;
    stop = std::min(stop, i);
    return false;
  });
  if (stop < rungs.size()) {
    results[stop].failure.thrown = thrown[stop];
    results[stop].failure.rethrow();
  }

  std::ostringstream csv;
  csv << "ladder,cells_per_diameter,cfl,dt_s,e,e_error_vs_finest,e_instant,wall_time_s,flow_steps,ms_per_flow_step,krylov_per_step\n";
  nlohmann::ordered_json js = {{"scene", base.name}, {"reference", "the finest rung of each ladder"}, {"rungs", nlohmann::ordered_json::array()}};
  std::cout << "work-precision of the coupled model, " << base.name << " (error against the finest rung of each ladder)\n";
  std::cout << std::left << std::setw(6) << "ladder" << std::right << std::setw(7) << "cells" << std::setw(7) << "cfl"
            << std::setw(11) << "dt s" << std::setw(9) << "e" << std::setw(11) << "|e-e_ref|" << std::setw(9) << "e_inst"
            << std::setw(9) << "wall s" << std::setw(7) << "steps" << std::setw(10) << "ms/step" << "\n";
  for (const char* ladder : {"grid", "step"}) {
    std::size_t ref = 0;
    for (std::size_t i = 0; i < rungs.size(); ++i)
      if (rungs[i].ladder == ladder) ref = i;
    const double e_ref = results[ref].e;
    for (std::size_t i = 0; i < rungs.size(); ++i) {
      const FlowRung& g = rungs[i];
      if (g.ladder != ladder) continue;
      const FlowRungResult& r = results[i];
      const double e = r.e, err = std::abs(e - e_ref);
      std::cout << std::left << std::setw(6) << ladder << std::right << std::setw(7) << g.cells << std::setw(7) << g.cfl
                << std::setw(11) << sci(r.dt, 2) << std::setw(9) << fixed(e, 4) << std::setw(11)
                << (i == ref ? std::string("ref") : sci(err, 2)) << std::setw(9) << fixed(r.e_instant, 4)
                << std::setw(9) << fixed(r.wall_time_s, 2) << std::setw(7) << r.steps
                << std::setw(10) << fixed(r.ms_per_step, 1) << "\n";
      csv << ladder << "," << g.cells << "," << csv_number(g.cfl) << "," << csv_number(r.dt) << ","
          << csv_number(e) << "," << csv_number(err) << "," << csv_number(r.e_instant) << ","
          << csv_number(r.wall_time_s) << "," << r.steps << ","
          << csv_number(r.ms_per_step) << "," << csv_number(r.krylov) << "\n";
      js["rungs"].push_back({{"ladder", ladder}, {"cells_per_diameter", g.cells}, {"cfl", g.cfl}, {"dt_s", r.dt}, {"e", e},
                             {"e_error_vs_finest", err}, {"e_instant", r.e_instant}, {"wall_time_s", r.wall_time_s},
                             {"flow", r.flow}});
    }
  }
  if (w.size > 1) js["ranks"] = w.size;
  js["run"] = unit->run();
  write_file_atomic(unit->dir() / "work_precision_flow.csv", csv.str());
  write_file_atomic(unit->dir() / "work_precision_flow.json", js.dump(2) + "\n");
  unit->commit();
  std::cout << "wrote " << (unit->target() / "work_precision_flow.csv").string() << " and .json\n";
  return 0;
}

}  // namespace imcol
