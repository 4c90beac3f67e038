// SPDX-License-Identifier: BSD-3-Clause
#include "apps/calibrate_files.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <variant>

#include "apps/sweep.hpp"
#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "core/report.hpp"
#include "run/json_util.hpp"

namespace imcol {

namespace fs = std::filesystem;
using calib::MeasuredTable;
using calib::MeasuredTrajectory;
using json = nlohmann::ordered_json;

namespace {

/// A double that reads back to itself (17 significant digits), for TOML and the CSV's parameter values.
std::string exact(double v) {
  std::string s;
  append_number(s, v, 17);
  return s;
}

/// A CSV cell: 12 significant digits; empty for a missing (non-finite) value.
std::string cell(double v) {
  std::string s;
  if (std::isfinite(v)) append_number(s, v, 12);
  return s;
}

/// Appends the cells to a CSV line, each after a comma.
template <class... Cells>
void add_cells(std::string& line, const Cells&... cells) {
  ((line += ',', line += cells), ...);
}

/// A word cell: commas and line ends would split it.
std::string word(std::string w) {
  for (char& c : w)
    if (c == ',' || c == '\n' || c == '\r') c = ';';
  return w;
}

json window_json(const MeasuredTrajectory& m, const calib::TrajectoryWindow& w) {
  const double from = w.t_contact + w.before, to = w.t_contact + w.after;
  const auto [k0, k1] = calib::window_rows(m, w);
  const std::size_t samples = k1 - k0;
  return {{"t_contact_s", w.t_contact}, {"before_s", w.before}, {"after_s", w.after}, {"from_s", from}, {"to_s", to}, {"samples", samples}};
}

/// The table column that varies across the rows (the first; the first column if none does).
std::string varied_key(const MeasuredTable& t) {
  for (std::size_t k = 0; k < t.keys.size(); ++k)
    for (const auto& row : t.values)
      if (row[k] != t.values.front()[k]) return t.keys[k];
  return t.keys.empty() ? "" : t.keys.front();
}

json measurement_json(const calib::Measurement& m, const std::optional<calib::TrajectoryWindow>& w) {
  json j;
  if (const auto* t = std::get_if<MeasuredTrajectory>(&m)) {
    j["path"] = t->path;
    j["kind"] = "trajectory";
    j["rows"] = t->t.size();
    j["columns"] = t->columns;
    j["window"] = window_json(*t, *w);
    const auto [k0, k1] = calib::window_rows(*t, *w);
    j["residuals"] = (k1 - k0) * t->columns.size();  // the window's samples x columns
    j["tau_max_s"] = w->tau_max;
    return j;
  }
  const auto& t = std::get<MeasuredTable>(m);
  j["path"] = t.path;
  j["kind"] = "table";
  j["rows"] = t.e.size();
  j["columns"] = t.keys;
  j["varied"] = varied_key(t);
  j["residuals"] = t.e.size();
  return j;
}

json evaluation_json(const calib::Evaluation& e) {
  json j;
  j["ok"] = e.ok;
  // A failed evaluation (or none at all: no best when none succeeded) has no objective.
  j["objective"] = e.ok ? run::finite_or_null(e.objective) : json(nullptr);
  j["rms"] = e.ok ? run::finite_or_null(e.rms) : json(nullptr);
  if (e.tau) j["tau_s"] = *e.tau;
  if (!e.message.empty()) j["message"] = e.message;
  return j;
}

json validation_json(const CalibrationRecord& rec) {
  json j = measurement_json(*rec.in.held_out, rec.in.held_window);
  j.update(evaluation_json(*rec.result.validation));
  if (std::holds_alternative<MeasuredTrajectory>(*rec.in.held_out)) {
    j["tau_refitted"] = true;  // the offset belongs to the measurement, not to the parameters
    return j;
  }
  const auto& t = std::get<MeasuredTable>(*rec.in.held_out);
  json rows = json::array();
  for (std::size_t r = 0; r < t.e.size(); ++r) {
    json row;
    row["line"] = t.lines[r];
    for (std::size_t k = 0; k < t.keys.size(); ++k) row[t.keys[k]] = t.values[r][k];
    row["e_meas"] = t.e[r];
    const auto& sim = rec.result.validation->e_sim;
    row["e_sim"] = r < sim.size() ? run::finite_or_null(sim[r]) : json(nullptr);
    rows.push_back(row);
  }
  j["by_row"] = rows;
  return j;
}

constexpr calib::Stage kStages[] = {calib::Stage::start, calib::Stage::scan, calib::Stage::local, calib::Stage::profile, calib::Stage::edge};

std::string calibration_csv(const CalibrationRecord& rec) {
  std::string out = "index,stage,item";
  for (const auto& p : rec.in.params) add_cells(out, p.key);
  out += ",objective,rms,tau_s,status,message,wall_ms,rank\n";
  const auto& ev = rec.result.search.evaluations;
  for (std::size_t i = 0; i < ev.size(); ++i) {
    const auto& e = ev[i];
    out += std::to_string(i);
    add_cells(out, std::string(calib::stage_name(e.stage)), std::to_string(e.item));
    for (double v : e.values) add_cells(out, exact(v));
    add_cells(out, cell(e.eval.objective), cell(e.eval.rms), e.eval.tau ? cell(*e.eval.tau) : std::string(),
              std::string(e.eval.ok ? "ok" : "failed"), word(e.eval.message), cell(1e3 * e.eval.wall_s), std::to_string(e.rank));
    out += '\n';
  }
  return out;
}

/// best.csv: a trajectory's fitted run on the measurement's clock (t + tau), its z columns; a table's rows with the
/// measured and the fitted e.
std::string best_csv(const CalibrationRecord& rec) {
  std::string out;
  const auto& best = rec.result.search.best_eval;
  if (rec.in.trajectory()) {
    const RunResult* run = rec.result.best_run ? &*rec.result.best_run : nullptr;
    std::vector<std::size_t> cols;
    out = "t";
    if (run)
      for (std::size_t c = 0; c < run->columns.size(); ++c)
        if (run->columns[c] == "z1" || run->columns[c] == "z2") {
          cols.push_back(c);
          add_cells(out, run->columns[c]);
        }
    out += "\n";
    if (!run) return out;
    const double tau = best.tau.value_or(0);
    for (const auto& row : run->rows) {
      out += cell(row[0] + tau);
      for (auto c : cols) add_cells(out, cell(row[c]));
      out += "\n";
    }
    return out;
  }
  const auto& t = std::get<MeasuredTable>(rec.in.data);
  out = "line";
  for (const auto& k : t.keys) add_cells(out, k);
  out += ",e_meas,e_sim\n";
  for (std::size_t r = 0; r < t.e.size(); ++r) {
    out += std::to_string(t.lines[r]);
    for (double v : t.values[r]) add_cells(out, cell(v));
    add_cells(out, cell(t.e[r]), r < best.e_sim.size() ? cell(best.e_sim[r]) : std::string());
    out += '\n';
  }
  return out;
}

json objective_json(bool trajectory) {
  return trajectory ? json{{"is", "mean square of z_sim(t - tau) - z_meas(t) over the window's samples and the measured columns, "
                                  "minimised over the time offset tau in [-tau_max, tau_max]"},
                           {"unit", "m^2"},
                           {"rms_unit", "m"}}
                    : json{{"is", "mean square of e_sim - e_meas over the rows"}, {"unit", "1"}, {"rms_unit", "1"}};
}

json parameters_json(const CalibrationRecord& rec) {
  json params = json::array();
  for (std::size_t k = 0; k < rec.in.params.size(); ++k) {
    const auto& p = rec.in.params[k];
    const auto& s = rec.in.start[k];
    params.push_back({{"key", p.key}, {"lo", p.lo}, {"hi", p.hi}, {"scale", p.scale == calib::Scale::log ? "log" : "linear"},
                      {"start", s.value}, {"scene_value", run::finite_or_null(s.scene)}, {"start_from", s.from}});
  }
  return params;
}

json search_json(const CalibrationRecord& rec) {
  const auto& so = rec.in.search;
  const int d = static_cast<int>(rec.in.params.size());
  return {{"scan", so.scan < 0 ? 8 * d + 1 : so.scan}, {"starts", so.starts}, {"max_evals", so.max_evals}, {"xtol", so.xtol},
          {"profile_points", so.profile_points}, {"factor", run::finite_or_null(so.factor)},
          {"confidence", so.factor ? json(nullptr) : json(so.confidence)}, {"refine", so.refine}, {"refine_to", so.refine_to}};
}

/// The best evaluation with its values by key.
json best_json(const CalibrationRecord& rec) {
  const auto& res = rec.result.search;
  json best = evaluation_json(res.best_eval);
  json values = json::object();
  for (std::size_t k = 0; k < rec.in.params.size() && k < res.best.size(); ++k) values[rec.in.params[k].key] = res.best[k];
  best["values"] = values;
  return best;
}

/// The evaluations counted by stage and by rank, with each stage's wall time.
json evaluations_json(const CalibrationRecord& rec) {
  const auto& res = rec.result.search;
  json by_stage = json::object(), stage_wall = json::object();
  for (auto s : kStages) {
    const auto n = std::count_if(res.evaluations.begin(), res.evaluations.end(), [s](const auto& e) { return e.stage == s; });
    if (!n) continue;
    by_stage[calib::stage_name(s)] = n;
    stage_wall[calib::stage_name(s)] = run::finite_or_null(rec.result.stage_times.wall(s));
  }
  std::vector<int> by_rank(static_cast<std::size_t>(std::max(1, rec.result.ranks)), 0);
  for (const auto& e : res.evaluations)
    if (e.rank >= 0 && static_cast<std::size_t>(e.rank) < by_rank.size()) ++by_rank[static_cast<std::size_t>(e.rank)];
  return {{"count", res.evaluations.size()}, {"failed", res.failed}, {"by_stage", by_stage}, {"by_rank", by_rank},
          {"stage_wall_s", stage_wall}, {"file", "calibration.csv"}};
}

json cache_json(const CalibrationRecord& rec) {
  return rec.cache ? json{{"path", rec.cache->path}, {"held", rec.cache->held}, {"reused", rec.cache->reused}, {"added", rec.cache->added}}
                   : json(nullptr);
}

/// Each parameter's profile with its interval (an end null: the objective stays within the factor up to the bound).
json profiles_json(const CalibrationRecord& rec) {
  const auto& res = rec.result.search;
  json profiles = json::array();
  const auto& rule = res.rule;
  const json factor_rule = rule.given ? json{{"kind", "given"}}
                                      : json{{"kind", "confidence"}, {"confidence", rule.confidence}, {"q", rule.q}, {"n", rule.n}, {"p", rule.p}};
  for (std::size_t k = 0; k < res.profiles.size() && k < rec.in.params.size(); ++k) {
    const auto& p = res.profiles[k];
    json obj = json::array();
    for (double v : p.objective) obj.push_back(run::finite_or_null(v));
    profiles.push_back({{"key", rec.in.params[k].key},
                        {"values", p.values},
                        {"objective", obj},
                        {"factor", run::finite_or_null(rule.factor)},
                        {"factor_rule", factor_rule},
                        {"threshold", run::finite_or_null(rule.threshold)},
                        {"interval", {{"lo", run::finite_or_null(p.lo)}, {"hi", run::finite_or_null(p.hi)}, {"resolved", p.resolved}}}});
  }
  return profiles;
}

/// best_run: the fitted run's blocks; a table's shared effects; or null (with best_run_error when it failed).
void add_best_run(json& j, const CalibrationRecord& rec, bool trajectory) {
  if (rec.result.best_run) {
    const auto& s = rec.result.best_run->summary_json;
    json br;
    for (const char* key : {"effects", "model", "solver", "e", "wall_time_s"})
      if (s.contains(key)) br[key] = s[key];
    j["best_run"] = br;
  } else if (!trajectory) {  // one run a row: the effects they share; their solver statistics are in no one run
    json effects = json::array();
    for (Effect e : rec.in.base.effects) effects.push_back(to_string(e));
    j["best_run"] = {{"effects", effects}, {"solver", nullptr}};
  } else {
    j["best_run"] = nullptr;
    if (!rec.result.best_run_error.empty()) j["best_run_error"] = rec.result.best_run_error;
  }
}

}  // namespace

json calibration_json(const CalibrationRecord& rec) {
  const bool trajectory = rec.in.trajectory();
  json j = scene_json(rec.in.scene_path, rec.in.overrides, rec.in.base);
  j["measurement"] = measurement_json(rec.in.data, rec.in.window);
  j["objective"] = objective_json(trajectory);
  j["parameters"] = parameters_json(rec);
  j["search"] = search_json(rec);
  j["best"] = best_json(rec);
  j["evaluations"] = evaluations_json(rec);
  j["cache"] = cache_json(rec);
  j["profiles"] = profiles_json(rec);
  if (rec.result.validation) j["validation"] = validation_json(rec);
  j["wall_time_s"] = rec.result.wall_s;
  j["jobs"] = rec.result.jobs;  // threads a rank
  j["ranks"] = rec.result.ranks;
  add_best_run(j, rec, trajectory);
  return j;
}

void write_calibration_files(const fs::path& dir, const CalibrationRecord& rec, const json& run) {
  write_file_atomic(dir / "measured.csv", rec.in.data_text);
  write_file_atomic(dir / "calibration.csv", calibration_csv(rec));
  write_file_atomic(dir / "best.csv", best_csv(rec));
  json j = calibration_json(rec);
  j["run"] = run;
  write_file_atomic(dir / "calibration.json", j.dump(2) + "\n");
}

}  // namespace imcol
