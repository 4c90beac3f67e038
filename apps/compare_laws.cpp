// SPDX-License-Identifier: BSD-3-Clause
#include "apps/compare_laws.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "apps/format.hpp"
#include "apps/option_rules.hpp"
#include "apps/output_unit.hpp"
#include "apps/plot.hpp"
#include "apps/table_csv.hpp"
#include "core/errors.hpp"
#include "core/work_scope.hpp"
#include "core/report.hpp"
#include "run/summary_json.hpp"
#include "run/simulate.hpp"
#include "study/laws.hpp"
#include "run/json_util.hpp"

namespace imcol {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

using study::LawRun;
using study::law_e;
using study::lookup;
using study::minus;

/// A short number for the table: 4 significant digits; "-" when missing.
std::string short_number(const std::optional<double>& v) {
  if (!v || !std::isfinite(*v)) return "-";
  std::ostringstream os;
  os << std::setprecision(4) << *v;
  return os.str();
}

std::string cell(const std::optional<double>& v, int p, double scale = 1) { return v ? fixed(scale * *v, p) : std::string("-"); }

/// The samples around the first contact (gap below 3 δ_SS) of every law that ran: law, t, gap, U_rel, f_contact1.
std::string traces_csv(const std::vector<LawRun>& rows) {
  std::ostringstream os;
  os << "law,t_s,gap_m,u_rel_m_s,f_contact_N\n";
  for (const auto& r : rows) {
    if (!r.ran() || !r.run.summary.contact) continue;
    const auto& cols = r.run.columns;
    auto col = [&](const char* name) {
      const auto it = std::find(cols.begin(), cols.end(), name);
      return it == cols.end() ? cols.size() : static_cast<std::size_t>(it - cols.begin());
    };
    const std::size_t it = col("t"), ig = col("gap"), iu = col("u_rel"), ifc = col("f_contact1");
    if (ig == cols.size() || iu == cols.size() || ifc == cols.size()) continue;
    const double zone = 3 * r.run.summary.contact->delta_ss_m;
    for (const auto& s : r.run.rows)
      if (s[ig] < zone)
        os << r.law << "," << csv_number(s[it]) << "," << csv_number(s[ig]) << "," << csv_number(s[iu]) << "," << csv_number(s[ifc]) << "\n";
  }
  return os.str();
}

/// The table of one scene: a line per law, then the named measures of e with a column per law that ran.
void print_scene_table(const std::vector<LawRun>& rows, const std::string& e_is) {
  std::cout << std::left << std::setw(8) << "law" << std::right << std::setw(9) << "e" << std::setw(10) << "e-e_ramp" << std::setw(9)
            << "St" << std::setw(12) << "contact us" << std::setw(11) << "max F_c N" << std::setw(16) << "max overlap um"
            << std::setw(7) << "steps" << std::setw(9) << "cpu ms" << "  law's numbers\n";
  for (const auto& r : rows) {
    std::cout << std::left << std::setw(8) << r.law << std::right;
    if (!r.ran()) {
      std::cout << "  " << r.status << ": " << r.message << "\n";
      continue;
    }
    const auto& s = r.run.summary;
    std::string numbers;
    for (const auto& [k, v] : study::law_numbers(r)) numbers += (numbers.empty() ? "" : ", ") + k + " = " + short_number(v);
    std::cout << std::setw(9) << cell(s.e, 4) << std::setw(10)
              << (r.law == "ramp" ? std::string("-") : cell(minus(s.e, study::ramp_e(rows, r.point)), 4)) << std::setw(9) << cell(s.St, 1)
              << std::setw(12) << cell(study::contact_time(r), 1, 1e6) << std::setw(11) << cell(study::peak_force(r), 1) << std::setw(16)
              << cell(study::max_overlap(r), 3, 1e6) << std::setw(7) << s.solver.stats.steps << std::setw(9) << fixed(1e3 * r.cpu_s, 1) << "  "
              << numbers << (r.message.empty() ? "" : "  (" + r.message + ")") << "\n";
  }
  const auto names = study::measure_names(rows);
  if (names.empty()) return;
  std::cout << std::left << std::setw(22) << "named measure" << std::right;
  for (const auto& r : rows)
    if (r.ran()) std::cout << std::setw(9) << r.law;
  std::cout << "\n";
  for (const auto& m : names) {
    std::cout << std::left << std::setw(22) << (to_string(m) == e_is ? std::string(to_string(m)) + " (e)" : std::string(to_string(m))) << std::right;
    for (const auto& r : rows)
      if (r.ran()) std::cout << std::setw(9) << cell(lookup(study::law_measures(r), m), 4);
    std::cout << "\n";
  }
}

/// The table of a sweep: a line per point with St and e of each law (and its difference from the ramp's), then per law
/// the points where it did not run, with the first reason.
void print_sweep_table(const std::vector<LawRun>& rows, const std::vector<std::string>& laws, const std::vector<double>& values,
                       const std::string& column) {
  const bool has_ramp = std::find(laws.begin(), laws.end(), "ramp") != laws.end();
  std::cout << std::setw(14) << column << std::setw(9) << "St";
  for (const auto& l : laws) std::cout << std::setw(10) << "e " + l;
  if (has_ramp)
    for (const auto& l : laws)
      if (l != "ramp") std::cout << std::setw(12) << l + "-ramp";
  std::cout << "\n";
  const std::size_t n = laws.size();
  for (std::size_t i = 0; i < values.size(); ++i) {
    const LawRun* at = &rows[i * n];  // rows run point by point, law by law
    std::optional<double> St;
    for (std::size_t k = 0; k < n && !St; ++k) St = at[k].ran() ? at[k].run.summary.St : std::nullopt;
    std::cout << std::setw(14) << std::setprecision(5) << std::defaultfloat << values[i] << std::setw(9) << cell(St, 2);
    for (std::size_t k = 0; k < n; ++k) std::cout << std::setw(10) << (at[k].ran() ? cell(law_e(at[k]), 4) : at[k].status);
    if (has_ramp)
      for (std::size_t k = 0; k < n; ++k)
        if (at[k].law != "ramp") std::cout << std::setw(12) << cell(minus(law_e(at[k]), study::ramp_e(rows, at[k].point)), 4);
    std::cout << "\n";
  }
  for (const auto& l : laws) {
    int missing = 0;
    const LawRun* first = nullptr;
    for (const auto& r : rows)
      if (r.law == l && (!r.ran() || !r.run.summary.e)) {
        ++missing;
        if (!first) first = &r;
      }
    if (first)
      std::cout << l << ": no e at " << missing << " of " << values.size() << " points; first at " << column << " = "
                << std::setprecision(5) << first->value << ": " << (first->ran() ? "" : first->status + ": ") << first->message << "\n";
  }
}

/// One row of laws.json.
Json law_json(const LawRun& r, const std::vector<LawRun>& rows) {
  Json j;
  if (r.point >= 0) {
    j["point"] = r.point;
    j["value"] = r.value;
  }
  j["law"] = r.law;
  j["status"] = r.status;
  j["message"] = r.message.empty() ? Json(nullptr) : Json(r.message);
  if (!r.ran()) return j;
  const auto& s = r.run.summary;
  j["e"] = run::finite_or_null(s.e);
  j["e_minus_e_ramp"] = run::finite_or_null(minus(s.e, study::ramp_e(rows, r.point)));
  j["St"] = run::finite_or_null(s.St);
  j["contact_time_s"] = run::finite_or_null(study::contact_time(r));
  j["max_contact_force_N"] = run::finite_or_null(study::peak_force(r));
  j["max_overlap_m"] = run::finite_or_null(study::max_overlap(r));
  j["min_gap_m"] = run::finite_or_null(s.min_gap_m);
  j["impact_speed_m_s"] = run::finite_or_null(s.contact ? s.contact->impact_speed_m_s : std::nullopt);
  j["steps"] = s.solver.stats.steps;
  j["rhs_evals"] = s.solver.stats.rhs_evals;
  j["cpu_time_s"] = r.cpu_s;
  j["wall_time_s"] = s.wall_time_s;
  j["setup_time_s"] = s.setup_time_s;
  Json jm = Json::object(), jn = Json::object(), model = Json::object();
  for (const auto& [k, v] : study::law_measures(r)) jm[to_string(k)] = run::finite_or_null(v);
  for (const auto& [k, v] : study::law_numbers(r)) jn[k] = run::finite_or_null(v);
  for (const auto& [k, v] : s.model)
    if (k.rfind("contact.", 0) == 0) model[k] = v;
  j["e_measures"] = jm;
  j["law_numbers"] = jn;
  j["model"] = model;
  j["warnings"] = s.warnings;
  return j;
}

/// laws.json, all but its `run` block.
Json laws_json(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base, const SweepOptions& sw,
               const char* column, const study::LawsResult& res) {
  Json j = scene_json(scene_path, overrides, base);  // laws refuse a free sphere
  j["e_is"] = res.e_is;
  if (res.contact) {
    j["e_dry"] = res.contact->e_dry;
    j["delta_ss_m"] = res.contact->delta_ss_m;
  }
  if (res.first_ran >= 0) j["effects"] = effects_to_json(res.rows[static_cast<std::size_t>(res.first_ran)].run.summary.effects);
  if (!sw.vary.empty()) put_sweep_settings(j, sw, column);
  Json jrows = Json::array();
  for (const auto& r : res.rows) jrows.push_back(law_json(r, res.rows));
  j["laws"] = jrows;
  return j;
}

/// The opening line: the scene, the sweep if any, e's measure, e_dry and delta_SS.
void print_heading(const Scene& base, const SweepOptions& sw, const study::LawsResult& res) {
  std::cout << "scene " << base.name << ": contact laws";
  if (!sw.vary.empty())
    std::cout << " at " << sw.points << " points of " << sw.vary << " from " << sw.from << " to " << sw.to << " (" << sw.spacing << " spacing)";
  std::cout << "; e = " << res.e_is;
  if (res.contact)
    std::cout << ", e_dry = " << short_number(res.contact->e_dry) << "; the laws act below delta_SS = " << fixed(1e6 * res.contact->delta_ss_m, 1)
              << " um";
  std::cout << "\n";
}

/// No law ran: a solver failure (exit 3) or the first law's refusal (exit 2), on one line; the table and laws.csv
/// hold every law's reason.
[[noreturn]] void throw_no_law_ran(const std::vector<LawRun>& rows, const OutputUnit& unit) {
  std::cout.flush();
  const std::string all = " (no contact law ran; every law's reason is in " + (unit.target() / "laws.csv").string() + ")";
  for (const auto& r : rows)
    if (r.failure) throw SolverError(r.law + ": " + r.failure->what() + all);
  const InputError& first = *rows.front().refusal;
  std::string problem = first.what();
  const std::string prefix = first.where() + (first.key().empty() ? "" : ": key '" + first.key() + "'") + ": ";
  if (problem.rfind(prefix, 0) == 0) problem.erase(0, prefix.size());
  throw InputError(first.where(), first.key(), rows.front().law + ": " + problem + all);
}

}  // namespace

int compare_laws(const std::string& scene_path, const std::vector<Override>& overrides, const LawsCompareOptions& opt) {
  const Scene base = load_scene(scene_path, overrides);
  if (!base.has_target())
    throw InputError(base.path, "wall", "a free sphere has no contact, so no contact law to compare (add a [wall] or a second [[sphere]])");
  const std::vector<std::string> laws = study::laws_to_compare(opt.laws, "command line", "--laws");
  const SweepOptions& sw = opt.sweep;
  const bool sweeping = !sw.vary.empty();
  const char* column = sweeping ? sweep_column(sw.vary) : "";
  if (!column) throw InputError("command line", "--vary", "unknown quantity '" + sw.vary + "' (expected velocity, viscosity, diameter, density)");
  if (sweeping && sw.points > 1 && sw.from == sw.to)
    throw InputError("command line", "--to", "equals --from: a sweep of several points needs a range");
  if (sweeping && sw.vary == "viscosity" && !base.fluid) throw InputError(base.path, "fluid", "a viscosity sweep needs a [fluid] table");
  OutputUnit unit(opt.out, fs::path("out") / (base.name + (sweeping ? "-laws_" + sw.vary : "-laws")), base.path);

  const auto load = [&](const std::vector<Override>& ov) { return load_scene(scene_path, ov); };
  const std::vector<double> values = sweeping ? sweep_values(sw) : std::vector<double>{};
  const study::LawsResult res = study::compare_laws(load, overrides, laws, sw.vary, values, true);
  this_thread_work().stop.throw_if_requested();  // Ctrl-C: nothing printed or kept of a stopped study
  print_heading(base, sw, res);
  if (sweeping) print_sweep_table(res.rows, laws, res.values, column);
  else print_scene_table(res.rows, res.e_is);

  Json j = laws_json(scene_path, overrides, base, sw, column, res);
  j["run"] = unit.run();
  write_file_atomic(unit.dir() / "laws.csv", table_csv(study::laws_table(res)));
  write_file_atomic(unit.dir() / "laws.json", j.dump(2) + "\n");
  if (!sweeping) write_file_atomic(unit.dir() / "laws_traces.csv", traces_csv(res.rows));
  if (opt.plot && res.first_ran >= 0) {
    std::cout.flush();
    run_plot_script("plot_laws.py", unit, "laws.png");
  }
  unit.commit();
  std::cout << "wrote " << (unit.target() / "laws.csv").string() << " and " << (unit.target() / "laws.json").string() << "\n";
  if (res.first_ran >= 0) return 0;
  throw_no_law_ran(res.rows, unit);
}

}  // namespace imcol
