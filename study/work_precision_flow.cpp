// SPDX-License-Identifier: BSD-3-Clause
#include "study/work_precision_flow.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "coupling/step_rule.hpp"
#include "run/json_util.hpp"
#include "run/simulate.hpp"
#include "run/summary.hpp"
#include "run/summary_json.hpp"
#include "study/run_all.hpp"
#include "study/run_failure.hpp"

namespace imcol::study {

namespace flow_ladder_impl {  // this file's helpers: named, as study/ is built in unity batches

/// What a rung's run tells the deciding process: e, e_instant, the wall time and the flow solver's block (as text,
/// its keys in order); or what it threw.
struct FlowRungOutcome {
  double e = NAN, e_instant = NAN, wall_time_s = NAN, dt = NAN, ms_per_step = NAN, krylov = NAN;
  long steps = 0;
  std::optional<FlowSummary> flow;
  RunFailure failure;
  int rank = 0;  // that ran it
};

void to_json(nlohmann::ordered_json& j, const FlowRungOutcome& r) {
  j = {{"e", r.e}, {"e_instant", r.e_instant}, {"wall_time_s", r.wall_time_s}, {"dt", r.dt}, {"ms_per_step", r.ms_per_step},
       {"krylov", r.krylov}, {"steps", r.steps}, {"flow", r.flow ? nlohmann::ordered_json(*r.flow) : nlohmann::ordered_json(nullptr)}, {"failure", r.failure}, {"rank", r.rank}};
}

void from_json(const nlohmann::ordered_json& j, FlowRungOutcome& r) {
  j.at("e").get_to(r.e), j.at("e_instant").get_to(r.e_instant), j.at("wall_time_s").get_to(r.wall_time_s);
  j.at("dt").get_to(r.dt), j.at("ms_per_step").get_to(r.ms_per_step), j.at("krylov").get_to(r.krylov);
  j.at("steps").get_to(r.steps), r.flow = run::get_opt<FlowSummary>(j, "flow"), j.at("failure").get_to(r.failure);
  j.at("rank").get_to(r.rank);
}

FlowRungOutcome run_flow_rung(const SceneLoader& load, const FlowRung& g) {
  FlowRungOutcome out;
  try {
    Scene sc = load({{"flow.cells_per_diameter", std::to_string(g.cells)}, {"flow.cfl", toml_float(g.cfl)}});
    sc.flow.fields = false;
    const RunResult run = simulate(sc);
    const auto& s = run.summary;
    const FlowSummary& f = s.flow.value();
    out.e = s.e.value_or(NAN), out.e_instant = s.e_instant.value_or(NAN), out.wall_time_s = s.wall_time_s;
    out.dt = f.stats.dt, out.ms_per_step = f.ms_per_step, out.krylov = f.krylov_iterations_per_step;
    out.steps = static_cast<long>(f.stats.steps);
    out.flow = f;
  } catch (const std::exception&) {
    out.failure = RunFailure::current();
  }
  return out;
}

/// The rows in rung order, each against the finest rung of its ladder.
std::vector<FlowLadderRow> ladder_rows(const std::vector<FlowRung>& rungs, const std::vector<FlowRungOutcome>& out) {
  std::vector<FlowLadderRow> rows;
  for (const char* ladder : {"grid", "step"}) {
    std::size_t ref = 0;
    for (std::size_t i = 0; i < rungs.size(); ++i)
      if (rungs[i].ladder == ladder) ref = i;
    for (std::size_t i = 0; i < rungs.size(); ++i) {
      if (rungs[i].ladder != ladder) continue;
      const FlowRungOutcome& r = out[i];
      FlowLadderRow row;
      row.ladder = rungs[i].ladder, row.cells = rungs[i].cells, row.cfl = rungs[i].cfl, row.reference = i == ref;
      row.dt = r.dt, row.e = r.e, row.err = std::abs(r.e - out[ref].e), row.e_instant = r.e_instant;
      row.wall_time_s = r.wall_time_s, row.ms_per_step = r.ms_per_step, row.krylov = r.krylov, row.steps = r.steps;
      row.flow = r.flow;
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

}  // namespace flow_ladder_impl

void check_flow_ladder(const Scene& base, const FlowLadderOptions& opt) {
  if (opt.cells.size() < 2 || opt.cfls.size() < 2) throw InputError("work-precision", "ladder", "each ladder needs two rungs or more");
  for (int c : opt.cells)
    if (c < 4 || c > 512) throw InputError("--cells", "cells", "cells per diameter must lie in [4, 512]");
  for (double c : opt.cfls)
    if (!(c > 0 && c <= 1)) throw InputError("--cfls", "cfls", "each cfl must lie in (0, 1]");
  if (base.flow.dt > 0) throw InputError(base.path, "flow.dt", "the step ladder varies flow.cfl: remove flow.dt from the scene");
}

std::vector<FlowRung> flow_rungs(const Scene& base, const FlowLadderOptions& opt) {
  std::vector<FlowRung> rungs;
  double u_ref = 0;  // the grid ladder keeps the scene's cfl, or the default cfl(Re) of coupling/step_rule.hpp
  for (const auto& sp : base.spheres) u_ref = std::max(u_ref, std::abs(sp.velocity));
  for (int c : opt.cells) {
    Scene at = base;
    at.flow.cells_per_diameter = c;
    rungs.push_back({"grid", c, base.flow.cfl > 0 ? base.flow.cfl : coupling::flow_step(at, 1.0, u_ref).cfl});
  }
  for (double f : opt.cfls) rungs.push_back({"step", base.flow.cells_per_diameter, f});
  return rungs;
}

FlowLadderResult flow_ladder(const Scene& base, const SceneLoader& load, const FlowLadderOptions& opt, const Executor& ex,
                             const Hooks& hooks, const RunNotice& notice) {
  using namespace flow_ladder_impl;
  check_flow_ladder(base, opt);
  const std::vector<FlowRung> rungs = flow_rungs(base, opt);
  std::vector<FlowRungOutcome> out(rungs.size());
  std::vector<std::exception_ptr> thrown(rungs.size());  // this process's runs: the exception itself is rethrown
  std::vector<char> arrived(rungs.size(), 0);
  std::size_t stop = rungs.size();  // a failed rung ends the study
  auto run = [&](std::size_t i) {
    if (ex.ranks == 1 && notice) notice(i, -1);
    FlowRungOutcome r = run_flow_rung(load, rungs[i]);
    r.rank = ex.rank;
    thrown[i] = r.failure.thrown;
    return r;
  };
  auto take = [&](std::size_t i, FlowRungOutcome&& r) {
    out[i] = std::move(r);
    arrived[i] = 1;
    if (ex.ranks > 1 && notice) notice(i, out[i].rank);
    if (out[i].failure.kind == RunFailure::none) return true;
    stop = std::min(stop, i);
    return false;
  };
  run_all<FlowRungOutcome>(ex, rungs.size(), run, take, hooks);
  if (!ex.deciding()) return {};
  if (stop < rungs.size()) {
    out[stop].failure.thrown = thrown[stop];
    out[stop].failure.rethrow();
  }
  FlowLadderResult res{base.name, {}, ex.ranks, std::count(arrived.begin(), arrived.end(), 0) > 0};
  if (!res.cancelled) res.rows = ladder_rows(rungs, out);  // each row needs its ladder's finest rung
  return res;
}

}  // namespace imcol::study
