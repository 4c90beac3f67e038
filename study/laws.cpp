// SPDX-License-Identifier: BSD-3-Clause
#include "study/laws.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>

namespace imcol::study {

namespace {

/// CPU seconds this process has used.
double process_cpu_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// The scene as given, with contact.law = `law` set last (it wins over a --set of the same key).
LawRun run_law(const SceneLoader& load, const std::vector<Override>& overrides, const std::string& law, bool progress) {
  LawRun row;
  row.law = law;
  auto ov = overrides;
  ov.push_back({"contact.law", "\"" + law + "\""});
  try {
    const Scene sc = load(ov);
    const double cpu0 = process_cpu_seconds();
    row.run = simulate(sc, progress);
    row.cpu_s = process_cpu_seconds() - cpu0;
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

/// Names in first-seen order over every row: the named measures of e, or the laws' numbers.
template <class Get>
auto union_of_names(const std::vector<LawRun>& rows, Get get) {
  std::vector<std::decay_t<decltype(get(rows.front()).front().first)>> names;
  for (const auto& r : rows)
    for (const auto& [k, v] : get(r))
      if (std::find(names.begin(), names.end(), k) == names.end()) names.push_back(k);
  return names;
}

/// What the first law that ran says of the scene: e's definition and the contact's e_dry and δ_SS.
void describe_scene(LawsResult& r, const Scene& base) {
  for (std::size_t i = 0; i < r.rows.size() && r.first_ran < 0; ++i)
    if (r.rows[i].ran()) r.first_ran = static_cast<int>(i);
  const LawRun* first = r.first_ran < 0 ? nullptr : &r.rows[static_cast<std::size_t>(r.first_ran)];
  r.e_is = to_string(first ? first->run.summary.e_is : base.measure.e);
  r.contact = first ? first->run.summary.contact : std::nullopt;
}

}  // namespace

std::optional<double> law_e(const LawRun& r) { return r.ran() ? r.run.summary.e : std::nullopt; }

std::optional<double> contact_time(const LawRun& r) {
  if (!r.ran() || !r.run.summary.contact) return std::nullopt;
  const auto& c = *r.run.summary.contact;
  if (!c.t_contact_s || !c.t_separation_s) return std::nullopt;
  return *c.t_separation_s - *c.t_contact_s;
}

std::optional<double> max_overlap(const LawRun& r) {
  if (!r.ran() || !r.run.summary.contact || !r.run.summary.min_gap_m) return std::nullopt;
  const double xi = r.run.summary.contact->delta_ss_m - *r.run.summary.min_gap_m;
  return xi > 0 ? std::optional<double>(xi) : std::nullopt;
}

std::optional<double> peak_force(const LawRun& r) { return r.ran() ? r.run.summary.max_contact_force_N : std::nullopt; }

std::optional<double> ramp_e(const std::vector<LawRun>& rows, int point) {
  for (const auto& r : rows)
    if (r.law == "ramp" && r.point == point) return law_e(r);
  return std::nullopt;
}

const std::vector<std::pair<std::string, std::optional<double>>>& law_numbers(const LawRun& r) {
  static const std::vector<std::pair<std::string, std::optional<double>>> none;
  return r.ran() && r.run.summary.contact ? r.run.summary.contact->law_numbers : none;
}

const std::vector<std::pair<EMeasure, std::optional<double>>>& law_measures(const LawRun& r) {
  static const std::vector<std::pair<EMeasure, std::optional<double>>> none;
  return r.ran() ? r.run.summary.e_measures : none;
}

std::vector<EMeasure> measure_names(const std::vector<LawRun>& rows) { return union_of_names(rows, law_measures); }

std::vector<std::string> laws_to_compare(const std::vector<std::string>& given, const std::string& where, const std::string& key) {
  std::vector<std::string> laws;
  for (const auto& l : given.empty() ? choice_names<ContactLawKind>() : given) {
    if (!choice_from_string<ContactLawKind>(l)) throw InputError(where, key, "unknown law '" + l + "'");
    if (std::find(laws.begin(), laws.end(), l) == laws.end()) laws.push_back(l);
  }
  return laws;
}

LawsResult compare_laws(const SceneLoader& load, const std::vector<Override>& overrides, const std::vector<std::string>& laws,
                        const std::string& vary, const std::vector<double>& values, bool progress, const Hooks& hooks) {
  const bool sweep = !vary.empty();
  const Scene base = load(overrides);
  if (!base.has_target())
    throw InputError(base.path, "wall", "a free sphere has no contact, so no contact law to compare (add a [wall] or a second [[sphere]])");
  if (sweep && vary == "viscosity" && !base.fluid) throw InputError(base.path, "fluid", "a viscosity sweep needs a [fluid] table");
  LawsResult r;
  r.laws = laws;
  if (sweep) r.vary = vary, r.column = sweep_column(vary);
  r.values = sweep ? values : std::vector<double>{NAN};
  const std::size_t total = r.values.size() * laws.size();
  WorkScope scope(run_control(hooks));  // a stop request ends the run in flight; its row is dropped
  for (std::size_t i = 0; i < r.values.size() && !r.cancelled; ++i) {
    auto ov = overrides;
    if (sweep)
      for (auto& o : sweep_overrides(base, vary, r.values[i])) ov.push_back(o);
    for (const auto& law : laws) {
      if ((r.cancelled = hooks.cancel_requested())) break;
      try {
        r.rows.push_back(run_law(load, ov, law, progress));
      } catch (const Interrupted&) {
        r.cancelled = true;
        break;
      }
      if (sweep) {  // its trajectory is not kept
        LawRun& row = r.rows.back();
        row.point = static_cast<int>(i);
        row.value = r.values[i];
        row.run.rows = {};
        row.run.contact_rows = {};
        row.run.summary_json = {};
      }
      if (hooks.progress) hooks.progress(r.rows.size(), total);
    }
  }
  describe_scene(r, base);
  return r;
}

namespace {

/// Adds a numeric column of `get` over the rows.
template <class Get>
void add_law_numbers(Table& t, const std::string& name, const std::vector<LawRun>& rows, Get get) {
  auto& c = t.add(name);
  for (const auto& r : rows) c.numbers.push_back(get(r).value_or(NAN));
}

/// steps .. setup_time_s: empty cells where the law did not run.
void add_law_costs(Table& t, const std::vector<LawRun>& rows) {
  using V = std::optional<double>;
  auto ran = [](const LawRun& r, double v) { return r.ran() ? V(v) : V(); };
  const auto& s = [](const LawRun& r) -> const RunSummary& { return r.run.summary; };
  add_law_numbers(t, "steps", rows, [&](const LawRun& r) { return ran(r, static_cast<double>(s(r).solver.stats.steps)); });
  add_law_numbers(t, "rhs_evals", rows, [&](const LawRun& r) { return ran(r, static_cast<double>(s(r).solver.stats.rhs_evals)); });
  add_law_numbers(t, "cpu_time_s", rows, [&](const LawRun& r) { return ran(r, r.cpu_s); });
  add_law_numbers(t, "wall_time_s", rows, [&](const LawRun& r) { return ran(r, s(r).wall_time_s); });
  add_law_numbers(t, "setup_time_s", rows, [&](const LawRun& r) { return ran(r, s(r).setup_time_s); });
}

}  // namespace

Table laws_table(const LawsResult& res) {
  using V = std::optional<double>;
  const auto& rows = res.rows;
  Table t;
  t.rows = rows.size();
  if (!res.column.empty()) {
    add_law_numbers(t, "point", rows, [](const LawRun& r) { return V(r.point); });
    add_law_numbers(t, res.column, rows, [](const LawRun& r) { return V(r.value); });
  }
  auto& law = t.add("law", true);
  auto& status = t.add("status", true);
  for (const auto& r : rows) law.text.push_back(r.law), status.text.push_back(r.status);
  auto if_ran = [](const LawRun& r, const V& v) { return r.ran() ? v : V(); };
  add_law_numbers(t, "e", rows, law_e);
  add_law_numbers(t, "e_minus_e_ramp", rows, [&](const LawRun& r) { return minus(law_e(r), ramp_e(rows, r.point)); });
  add_law_numbers(t, "St", rows, [&](const LawRun& r) { return if_ran(r, r.run.summary.St); });
  add_law_numbers(t, "contact_time_s", rows, contact_time);
  add_law_numbers(t, "max_contact_force_N", rows, peak_force);
  add_law_numbers(t, "max_overlap_m", rows, max_overlap);
  add_law_numbers(t, "min_gap_m", rows, [&](const LawRun& r) { return if_ran(r, r.run.summary.min_gap_m); });
  add_law_numbers(t, "impact_speed_m_s", rows, [](const LawRun& r) {
    return r.ran() && r.run.summary.contact ? r.run.summary.contact->impact_speed_m_s : V();
  });
  add_law_costs(t, rows);
  for (const auto& m : measure_names(rows))
    add_law_numbers(t, std::string("e_") + to_string(m), rows, [&](const LawRun& r) { return lookup(law_measures(r), m); });
  for (const auto& n : union_of_names(rows, law_numbers))
    add_law_numbers(t, "law_" + n, rows, [&](const LawRun& r) { return lookup(law_numbers(r), n); });
  auto& message = t.add("message", true);
  for (const auto& r : rows) message.text.push_back(r.message);
  return t;
}

}  // namespace imcol::study
