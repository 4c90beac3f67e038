// SPDX-License-Identifier: BSD-3-Clause
#include "apps/work_precision_flow.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/format.hpp"
#include "run/json_util.hpp"
#include "run/simulate.hpp"
#include "run/summary.hpp"
#include "core/errors.hpp"
#include "core/report.hpp"
#include "coupling/step_rule.hpp"

namespace imcol {

namespace {

struct Rung {
  std::string ladder;
  int cells;
  double cfl;
  RunResult run;
};

}  // namespace

int work_precision_flow(const Scene& base, const std::vector<Override>& overrides, const FlowLadderOptions& opt, OutputUnit& unit) {
  if (opt.cells.size() < 2 || opt.cfls.size() < 2) throw InputError("work-precision", "ladder", "each ladder needs two rungs or more");
  for (int c : opt.cells)
    if (c < 4 || c > 512) throw InputError("--cells", "cells", "cells per diameter must lie in [4, 512]");
  for (double c : opt.cfls)
    if (!(c > 0 && c <= 1)) throw InputError("--cfls", "cfls", "each cfl must lie in (0, 1]");
  if (base.flow.dt > 0) throw InputError(base.path, "flow.dt", "the step ladder varies flow.cfl: remove flow.dt from the scene");
  std::vector<Rung> rungs;
  auto run = [&](const std::string& ladder, int cells, double cfl) {
    auto ov = overrides;
    ov.push_back({"flow.cells_per_diameter", std::to_string(cells)});
    std::ostringstream c;
    c << std::setprecision(17) << cfl;
    ov.push_back({"flow.cfl", c.str()});
    Scene sc = load_scene(base.path, ov);
    sc.flow.fields = false;
    std::cerr << "  " << ladder << ": " << cells << " cells/D, cfl " << cfl << " ...\n";
    rungs.push_back({ladder, cells, cfl, simulate(sc)});
  };
  double u_ref = 0;  // the grid ladder keeps the scene's cfl, or the default cfl(Re) of coupling/step_rule.hpp
  for (const auto& sp : base.spheres) u_ref = std::max(u_ref, std::abs(sp.velocity));
  for (int c : opt.cells) {
    Scene at = base;
    at.flow.cells_per_diameter = c;
    run("grid", c, base.flow.cfl > 0 ? base.flow.cfl : coupling::flow_step(at, 1.0, u_ref).cfl);
  }
  for (double f : opt.cfls) run("step", base.flow.cells_per_diameter, f);

  std::ostringstream csv;
  csv << "ladder,cells_per_diameter,cfl,dt_s,e,e_error_vs_finest,e_instant,wall_time_s,flow_steps,ms_per_flow_step,krylov_per_step\n";
  nlohmann::ordered_json js = {{"scene", base.name}, {"reference", "the finest rung of each ladder"}, {"rungs", nlohmann::ordered_json::array()}};
  std::cout << "work-precision of the coupled model, " << base.name << " (error against the finest rung of each ladder)\n";
  std::cout << std::left << std::setw(6) << "ladder" << std::right << std::setw(7) << "cells" << std::setw(7) << "cfl"
            << std::setw(11) << "dt s" << std::setw(9) << "e" << std::setw(11) << "|e-e_ref|" << std::setw(9) << "e_inst"
            << std::setw(9) << "wall s" << std::setw(7) << "steps" << std::setw(10) << "ms/step" << "\n";
  for (const char* ladder : {"grid", "step"}) {
    const Rung* ref = nullptr;
    for (const auto& r : rungs)
      if (r.ladder == ladder) ref = &r;
    const double e_ref = ref->run.summary.e.value_or(NAN);
    for (const auto& r : rungs) {
      if (r.ladder != ladder) continue;
      const auto& s = r.run.summary;
      const FlowSummary& f = s.flow.value();
      const double e = s.e.value_or(NAN), err = std::abs(e - e_ref);
      std::cout << std::left << std::setw(6) << ladder << std::right << std::setw(7) << r.cells << std::setw(7) << r.cfl
                << std::setw(11) << sci(f.stats.dt, 2) << std::setw(9) << fixed(e, 4) << std::setw(11)
                << (&r == ref ? std::string("ref") : sci(err, 2)) << std::setw(9) << fixed(s.e_instant.value_or(NAN), 4)
                << std::setw(9) << fixed(s.wall_time_s, 2) << std::setw(7) << f.stats.steps
                << std::setw(10) << fixed(f.ms_per_step, 1) << "\n";
      csv << ladder << "," << r.cells << "," << csv_number(r.cfl) << "," << csv_number(f.stats.dt) << ","
          << csv_number(e) << "," << csv_number(err) << "," << csv_number(s.e_instant.value_or(NAN)) << ","
          << csv_number(s.wall_time_s) << "," << f.stats.steps << ","
          << csv_number(f.ms_per_step) << "," << csv_number(f.krylov_iterations_per_step) << "\n";
      js["rungs"].push_back({{"ladder", ladder}, {"cells_per_diameter", r.cells}, {"cfl", r.cfl}, {"dt_s", f.stats.dt}, {"e", run::or_null(s.e)},
                             {"e_error_vs_finest", err}, {"e_instant", run::or_null(s.e_instant)}, {"wall_time_s", s.wall_time_s},
                             {"flow", run::flow_block(f)}});
    }
  }
  js["run"] = unit.run();
  write_file_atomic(unit.dir() / "work_precision_flow.csv", csv.str());
  write_file_atomic(unit.dir() / "work_precision_flow.json", js.dump(2) + "\n");
  unit.commit();
  std::cout << "wrote " << (unit.target() / "work_precision_flow.csv").string() << " and .json\n";
  return 0;
}

}  // namespace imcol
