// SPDX-License-Identifier: BSD-3-Clause
#include "apps/compare_laws.hpp"

#include <time.h>

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
#include "core/errors.hpp"
#include "core/report.hpp"
#include "run/simulate.hpp"
#include "run/summary_json.hpp"
#include "run/json_util.hpp"

namespace imcol {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

/// One law's run, or why there is none.
struct LawRow {
  std::string law;
  std::string status = "ran";  // ran | refused (bad input for this law) | failed (the solver)
  std::string message;         // refused/failed: the error; ran: why e is missing, if it is
  std::optional<InputError> refusal;
  std::optional<SolverError> failure;
  RunResult run;
  double cpu_s = NAN;  // process CPU time of the whole run (model set-up included), s
  int point = -1;      // a sweep's point (-1: the scene alone) and the varied quantity's value there
  double value = NAN;
  bool ran() const { return status == "ran"; }
};

/// CPU seconds this process has used.
double cpu_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// A TOML string literal.
std::string toml_string(const std::string& s) { return "\"" + s + "\""; }

/// The scene as given, with contact.law = `law` set last (it wins over a --set of the same key).
LawRow run_law(const std::string& scene_path, const std::vector<Override>& overrides, const std::string& law) {
  LawRow row;
  row.law = law;
  auto ov = overrides;
  ov.push_back({"contact.law", toml_string(law)});
  try {
    const Scene sc = load_scene(scene_path, ov);
    const double cpu0 = cpu_seconds();
    row.run = simulate(sc, true);  // a progress line on a terminal if the run takes long (a coupled scene)
    row.cpu_s = cpu_seconds() - cpu0;
    if (!row.run.summary.e) row.message = row.run.summary.e_missing.value_or("e is undefined");
  } catch (const InputError& e) {
    row.status = "refused";
    row.message = e.what();
    row.refusal = e;
  } catch (const SolverError& e) {
    row.status = "failed";
    row.message = e.what();
    row.failure = e;
  }
  return row;
}

// The measured quantities of a row that ran (nullopt where the run has none).
std::optional<double> e_of(const LawRow& r) { return r.ran() ? r.run.summary.e : std::nullopt; }

/// Time below δ_SS in the first contact, s.
std::optional<double> contact_time(const LawRow& r) {
  if (!r.ran() || !r.run.summary.contact) return std::nullopt;
  const auto& c = *r.run.summary.contact;
  if (!c.t_contact_s || !c.t_separation_s) return std::nullopt;
  return *c.t_separation_s - *c.t_contact_s;
}

/// The deepest overlap δ_SS − min gap, m (both laws act below δ_SS; Hertz's indentation ξ, the ramp's depth into its zone).
std::optional<double> max_overlap(const LawRow& r) {
  if (!r.ran() || !r.run.summary.contact || !r.run.summary.min_gap_m) return std::nullopt;
  const double xi = r.run.summary.contact->delta_ss_m - *r.run.summary.min_gap_m;
  return xi > 0 ? std::optional<double>(xi) : std::nullopt;
}

std::optional<double> peak_force(const LawRow& r) { return r.ran() ? r.run.summary.max_contact_force_N : std::nullopt; }

std::optional<double> minus(const std::optional<double>& a, const std::optional<double>& b) {
  return a && b ? std::optional<double>(*a - *b) : std::nullopt;
}

/// The law's own summary numbers (ContactLaw::summary), name → value.
const std::vector<std::pair<std::string, std::optional<double>>>& law_numbers(const LawRow& r) {
  static const std::vector<std::pair<std::string, std::optional<double>>> none;
  return r.ran() && r.run.summary.contact ? r.run.summary.contact->law_numbers : none;
}

/// Names in first-seen order over every row: the named measures of e, or the laws' numbers.
template <class Get>
auto union_of_names(const std::vector<LawRow>& rows, Get get) {
  std::vector<std::decay_t<decltype(get(rows.front()).front().first)>> names;
  for (const auto& r : rows)
    for (const auto& [k, v] : get(r))
      if (std::find(names.begin(), names.end(), k) == names.end()) names.push_back(k);
  return names;
}

template <class K>
std::optional<double> lookup(const std::vector<std::pair<K, std::optional<double>>>& list, const K& name) {
  for (const auto& [k, v] : list)
    if (k == name) return v;
  return std::nullopt;
}

const std::vector<std::pair<EMeasure, std::optional<double>>>& measures(const LawRow& r) {
  static const std::vector<std::pair<EMeasure, std::optional<double>>> none;
  return r.ran() ? r.run.summary.e_measures : none;
}

/// A short number for the table: 4 significant digits; "-" when missing.
std::string short_number(const std::optional<double>& v) {
  if (!v || !std::isfinite(*v)) return "-";
  std::ostringstream os;
  os << std::setprecision(4) << *v;
  return os.str();
}

std::string cell(const std::optional<double>& v, int p, double scale = 1) { return v ? fixed(scale * *v, p) : std::string("-"); }

/// The samples around the first contact (gap below 3 δ_SS) of every law that ran: law, t, gap, U_rel, f_contact1.
std::string traces_csv(const std::vector<LawRow>& rows) {
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

/// e of the ramp (the default law) at the same point, if it ran there: what e − e_ramp compares with.
std::optional<double> ramp_e(const std::vector<LawRow>& rows, int point) {
  for (const auto& r : rows)
    if (r.law == "ramp" && r.point == point) return e_of(r);
  return std::nullopt;
}

/// The table of one scene: a line per law, then the named measures of e with a column per law that ran.
void print_scene_table(const std::vector<LawRow>& rows, const std::string& e_is) {
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
    for (const auto& [k, v] : law_numbers(r)) numbers += (numbers.empty() ? "" : ", ") + k + " = " + short_number(v);
    std::cout << std::setw(9) << cell(s.e, 4) << std::setw(10)
              << (r.law == "ramp" ? std::string("-") : cell(minus(s.e, ramp_e(rows, r.point)), 4)) << std::setw(9) << cell(s.St, 1)
              << std::setw(12) << cell(contact_time(r), 1, 1e6) << std::setw(11) << cell(peak_force(r), 1) << std::setw(16)
              << cell(max_overlap(r), 3, 1e6) << std::setw(7) << s.solver.stats.steps << std::setw(9) << fixed(1e3 * r.cpu_s, 1) << "  "
              << numbers << (r.message.empty() ? "" : "  (" + r.message + ")") << "\n";
  }
  const auto names = union_of_names(rows, measures);
  if (names.empty()) return;
  std::cout << std::left << std::setw(22) << "named measure" << std::right;
  for (const auto& r : rows)
    if (r.ran()) std::cout << std::setw(9) << r.law;
  std::cout << "\n";
  for (const auto& m : names) {
    std::cout << std::left << std::setw(22) << (to_string(m) == e_is ? std::string(to_string(m)) + " (e)" : std::string(to_string(m))) << std::right;
    for (const auto& r : rows)
      if (r.ran()) std::cout << std::setw(9) << cell(lookup(measures(r), m), 4);
    std::cout << "\n";
  }
}

/// The table of a sweep: a line per point with St and e of each law (and its difference from the ramp's), then per law
/// the points where it did not run, with the first reason.
void print_sweep_table(const std::vector<LawRow>& rows, const std::vector<std::string>& laws, const std::vector<double>& values,
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
    const LawRow* at = &rows[i * n];  // rows run point by point, law by law
    std::optional<double> St;
    for (std::size_t k = 0; k < n && !St; ++k) St = at[k].ran() ? at[k].run.summary.St : std::nullopt;
    std::cout << std::setw(14) << std::setprecision(5) << std::defaultfloat << values[i] << std::setw(9) << cell(St, 2);
    for (std::size_t k = 0; k < n; ++k) std::cout << std::setw(10) << (at[k].ran() ? cell(e_of(at[k]), 4) : at[k].status);
    if (has_ramp)
      for (std::size_t k = 0; k < n; ++k)
        if (at[k].law != "ramp") std::cout << std::setw(12) << cell(minus(e_of(at[k]), ramp_e(rows, at[k].point)), 4);
    std::cout << "\n";
  }
  for (const auto& l : laws) {
    int missing = 0;
    const LawRow* first = nullptr;
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

/// laws.csv: a row per law (and sweep point), the named measures and the laws' numbers as columns of their own.
std::string laws_csv(const std::vector<LawRow>& rows, const std::string& column) {
  const auto measure_names = union_of_names(rows, measures);
  const auto number_names = union_of_names(rows, law_numbers);
  std::ostringstream csv;
  if (!column.empty()) csv << "point," << column << ",";
  csv << "law,status,e,e_minus_e_ramp,St,contact_time_s,max_contact_force_N,max_overlap_m,min_gap_m,impact_speed_m_s,steps,rhs_evals,"
         "cpu_time_s,wall_time_s,setup_time_s";
  for (const auto& m : measure_names) csv << ",e_" << to_string(m);
  for (const auto& n : number_names) csv << ",law_" << n;
  csv << ",message\n";
  for (const auto& r : rows) {
    const auto& s = r.run.summary;
    auto if_ran = [&](const std::optional<double>& v) { return r.ran() ? v : std::nullopt; };
    std::string msg = r.message;
    for (char& c : msg)
      if (c == ',' || c == '\n') c = ';';
    if (!column.empty()) csv << r.point << "," << csv_number(r.value) << ",";
    csv << r.law << "," << r.status << "," << csv_cell(e_of(r)) << "," << csv_cell(minus(e_of(r), ramp_e(rows, r.point))) << ","
        << csv_cell(if_ran(s.St)) << "," << csv_cell(contact_time(r)) << "," << csv_cell(peak_force(r)) << ","
        << csv_cell(max_overlap(r)) << "," << csv_cell(if_ran(s.min_gap_m)) << ","
        << csv_cell(r.ran() && s.contact ? s.contact->impact_speed_m_s : std::nullopt);
    if (r.ran())
      csv << "," << s.solver.stats.steps << "," << s.solver.stats.rhs_evals << "," << csv_number(r.cpu_s) << "," << csv_number(s.wall_time_s)
          << "," << csv_number(s.setup_time_s);
    else
      csv << ",,,,,";
    for (const auto& m : measure_names) csv << "," << csv_cell(lookup(measures(r), m));
    for (const auto& n : number_names) csv << "," << csv_cell(lookup(law_numbers(r), n));
    csv << "," << msg << "\n";
  }
  return csv.str();
}

/// One row of laws.json.
Json law_json(const LawRow& r, const std::vector<LawRow>& rows) {
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
  j["e_minus_e_ramp"] = run::finite_or_null(minus(s.e, ramp_e(rows, r.point)));
  j["St"] = run::finite_or_null(s.St);
  j["contact_time_s"] = run::finite_or_null(contact_time(r));
  j["max_contact_force_N"] = run::finite_or_null(peak_force(r));
  j["max_overlap_m"] = run::finite_or_null(max_overlap(r));
  j["min_gap_m"] = run::finite_or_null(s.min_gap_m);
  j["impact_speed_m_s"] = run::finite_or_null(s.contact ? s.contact->impact_speed_m_s : std::nullopt);
  j["steps"] = s.solver.stats.steps;
  j["rhs_evals"] = s.solver.stats.rhs_evals;
  j["cpu_time_s"] = r.cpu_s;
  j["wall_time_s"] = s.wall_time_s;
  j["setup_time_s"] = s.setup_time_s;
  Json jm = Json::object(), jn = Json::object(), model = Json::object();
  for (const auto& [k, v] : measures(r)) jm[to_string(k)] = run::finite_or_null(v);
  for (const auto& [k, v] : law_numbers(r)) jn[k] = run::finite_or_null(v);
  for (const auto& [k, v] : s.model)
    if (k.rfind("contact.", 0) == 0) model[k] = v;
  j["e_measures"] = jm;
  j["law_numbers"] = jn;
  j["model"] = model;
  j["warnings"] = s.warnings;
  return j;
}

/// The laws to compare: --laws (unknown names refused, repeats dropped), or every shipped law.
std::vector<std::string> laws_to_compare(const LawsCompareOptions& opt) {
  std::vector<std::string> laws;
  for (const auto& l : opt.laws.empty() ? choice_names<ContactLawKind>() : opt.laws) {
    if (!choice_from_string<ContactLawKind>(l)) throw InputError("command line", "--laws", "unknown law '" + l + "'");
    if (std::find(laws.begin(), laws.end(), l) == laws.end()) laws.push_back(l);
  }
  return laws;
}

/// Point by point (one point, NaN, without --vary), law by law; a sweep's point keeps its summary only.
std::vector<LawRow> run_laws(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base,
                             const std::vector<std::string>& laws, const SweepOptions& sw, const std::vector<double>& values) {
  const bool sweeping = !sw.vary.empty();
  std::vector<LawRow> rows;
  for (std::size_t i = 0; i < values.size(); ++i) {
    auto ov = overrides;
    if (sweeping)
      for (auto& o : sweep_overrides(base, sw.vary, values[i])) ov.push_back(o);
    for (const auto& law : laws) {
      rows.push_back(run_law(scene_path, ov, law));
      if (sweeping) {  // its trajectory is not written
        LawRow& r = rows.back();
        r.point = static_cast<int>(i);
        r.value = values[i];
        r.run.rows = {};
        r.run.contact_rows = {};
        r.run.summary_json = {};
      }
    }
  }
  return rows;
}

/// What the first law that ran says of the scene: e's definition and the contact's e_dry and δ_SS.
struct LawsContext {
  const LawRow* first_ran = nullptr;
  std::string e_is;
  std::optional<ContactSummary> contact;
};

/// laws.json, all but its `run` block.
Json laws_json(const std::string& scene_path, const std::vector<Override>& overrides, const Scene& base, const SweepOptions& sw,
               const char* column, const LawsContext& cx, const std::vector<LawRow>& rows) {
  Json j = scene_json(scene_path, overrides, base);  // laws refuse a free sphere
  j["e_is"] = cx.e_is;
  if (cx.contact) {
    j["e_dry"] = cx.contact->e_dry;
    j["delta_ss_m"] = cx.contact->delta_ss_m;
  }
  if (cx.first_ran) j["effects"] = effects_to_json(cx.first_ran->run.summary.effects);
  if (!sw.vary.empty()) put_sweep_settings(j, sw, column);
  Json jrows = Json::array();
  for (const auto& r : rows) jrows.push_back(law_json(r, rows));
  j["laws"] = jrows;
  return j;
}

/// No law ran: a solver failure (exit 3) or the first law's refusal (exit 2), on one line; the table and laws.csv
/// hold every law's reason.
[[noreturn]] void throw_no_law_ran(const std::vector<LawRow>& rows, const OutputUnit& unit) {
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
  const std::vector<std::string> laws = laws_to_compare(opt);
  const SweepOptions& sw = opt.sweep;
  const bool sweeping = !sw.vary.empty();
  const char* column = sweeping ? sweep_column(sw.vary) : "";
  if (!column) throw InputError("command line", "--vary", "unknown quantity '" + sw.vary + "' (expected velocity, viscosity, diameter, density)");
  if (sweeping && sw.points > 1 && sw.from == sw.to)
    throw InputError("command line", "--to", "equals --from: a sweep of several points needs a range");
  if (sweeping && sw.vary == "viscosity" && !base.fluid) throw InputError(base.path, "fluid", "a viscosity sweep needs a [fluid] table");
  OutputUnit unit(opt.out, fs::path("out") / (base.name + (sweeping ? "-laws_" + sw.vary : "-laws")), base.path);

  const std::vector<double> values = sweeping ? sweep_values(sw) : std::vector<double>{NAN};
  const std::vector<LawRow> rows = run_laws(scene_path, overrides, base, laws, sw, values);
  LawsContext cx;
  for (const auto& r : rows)
    if (r.ran() && !cx.first_ran) cx.first_ran = &r;
  cx.e_is = to_string(cx.first_ran ? cx.first_ran->run.summary.e_is : base.measure.e);
  cx.contact = cx.first_ran ? cx.first_ran->run.summary.contact : std::nullopt;
  const std::string& e_is = cx.e_is;
  const std::optional<ContactSummary>& contact = cx.contact;

  std::cout << "scene " << base.name << ": contact laws";
  if (sweeping)
    std::cout << " at " << sw.points << " points of " << sw.vary << " from " << sw.from << " to " << sw.to << " (" << sw.spacing << " spacing)";
  std::cout << "; e = " << e_is;
  if (contact) std::cout << ", e_dry = " << short_number(contact->e_dry) << "; the laws act below delta_SS = " << fixed(1e6 * contact->delta_ss_m, 1) << " um";
  std::cout << "\n";
  if (sweeping) print_sweep_table(rows, laws, values, column);
  else print_scene_table(rows, e_is);

  Json j = laws_json(scene_path, overrides, base, sw, column, cx, rows);
  j["run"] = unit.run();
  write_file_atomic(unit.dir() / "laws.csv", laws_csv(rows, column));
  write_file_atomic(unit.dir() / "laws.json", j.dump(2) + "\n");
  if (!sweeping) write_file_atomic(unit.dir() / "laws_traces.csv", traces_csv(rows));
  if (opt.plot && cx.first_ran) {
    std::cout.flush();
    run_plot_script("plot_laws.py", unit, "laws.png");
  }
  unit.commit();
  std::cout << "wrote " << (unit.target() / "laws.csv").string() << " and " << (unit.target() / "laws.json").string() << "\n";
  if (cx.first_ran) return 0;
  throw_no_law_ran(rows, unit);
}

}  // namespace imcol
