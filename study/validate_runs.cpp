// SPDX-License-Identifier: BSD-3-Clause
// The seed validation's runs (study/validate.hpp): each Table 6.1 run with each model, at V_Io and at the speed that
// gives the printed St_B, on an Executor.
#include <cmath>
#include <exception>
#include <iomanip>
#include <optional>
#include <sstream>
#include <tuple>
#include <utility>

#include "core/errors.hpp"
#include "core/materials.hpp"
#include "core/report.hpp"
#include "run/simulate.hpp"
#include "study/run_all.hpp"
#include "study/run_failure.hpp"
#include "study/validate.hpp"
#include "study/validate_speed.hpp"

namespace imcol::study {

/// One run's measures as JSON (rows cross ranks so): every field by its name.
void to_json(nlohmann::ordered_json& j, const ValidateMeasures& m) {
  j = {{"St", m.St}, {"St_B_table_6_1", m.St_B_table_6_1}, {"St_B_eq_6_2", m.St_B_eq_6_2}, {"e", m.e}, {"e_instant", m.e_instant},
       {"Re", m.Re}, {"group_velocity_m_s", m.group_velocity_m_s}, {"steps", m.steps}, {"wall_time_s", m.wall_time_s},
       {"flow_steps", m.flow_steps}, {"flow_ms_per_step", m.flow_ms_per_step}, {"cells_per_diameter", m.cells_per_diameter},
       {"flow_dt_s", m.flow_dt_s}};
}
void from_json(const nlohmann::ordered_json& j, ValidateMeasures& m) {
  j.at("St").get_to(m.St), j.at("St_B_table_6_1").get_to(m.St_B_table_6_1), j.at("St_B_eq_6_2").get_to(m.St_B_eq_6_2);
  j.at("e").get_to(m.e), j.at("e_instant").get_to(m.e_instant), j.at("Re").get_to(m.Re);
  j.at("group_velocity_m_s").get_to(m.group_velocity_m_s), j.at("steps").get_to(m.steps), j.at("wall_time_s").get_to(m.wall_time_s);
  j.at("flow_steps").get_to(m.flow_steps), j.at("flow_ms_per_step").get_to(m.flow_ms_per_step);
  j.at("cells_per_diameter").get_to(m.cells_per_diameter), j.at("flow_dt_s").get_to(m.flow_dt_s);
}

/// A row as JSON (rows cross ranks so).
void to_json(nlohmann::ordered_json& j, const ValidateRow& r) {
  j = {{"seed", r.seed}, {"model", r.model}, {"set", static_cast<int>(r.set)}, {"V", r.V}, {"run", r.run}, {"reduced", r.reduced},
       {"warning", r.warning}};
}
void from_json(const nlohmann::ordered_json& j, ValidateRow& r) {
  j.at("seed").get_to(r.seed), j.at("model").get_to(r.model), j.at("V").get_to(r.V);
  r.set = static_cast<SpeedSet>(j.at("set").get<int>());
  j.at("run").get_to(r.run), j.at("reduced").get_to(r.reduced), j.at("warning").get_to(r.warning);
}

namespace validate_runs_impl {  // this file's helpers: named, as study/ is built in unity batches

/// The overrides without the [flow] ones (for the reduced-order runs beside coupled ones).
std::vector<Override> without_flow_keys(const std::vector<Override>& ov) {
  std::vector<Override> out;
  for (const auto& o : ov)
    if (o.key.rfind("flow.", 0) != 0) out.push_back(o);
  return out;
}

/// The scene with the `flow` effect added to its effects (coupled runs of the shipped reduced-order scenes).
Scene with_flow(const std::string& path, std::vector<Override> ov) {
  const Scene plain = load_scene(path, without_flow_keys(ov));  // the scene's own effects
  std::string list = "[";
  for (Effect e : plain.effects) list += std::string("\"") + to_string(e) + "\",";
  list += "\"flow\"]";
  ov.push_back({"effects", list});
  return load_scene(path, ov);
}

ValidateMeasures measures_of(const RunSummary& s) {
  ValidateMeasures m;
  m.St = s.St.value_or(NAN), m.St_B_table_6_1 = s.St_B_table_6_1.value_or(NAN), m.St_B_eq_6_2 = s.St_B_eq_6_2.value_or(NAN);
  m.e = s.e.value_or(NAN), m.e_instant = s.e_instant.value_or(NAN), m.Re = s.Re.value_or(NAN);
  m.group_velocity_m_s = s.group_velocity_m_s.value_or(NAN);
  m.steps = static_cast<double>(s.solver.stats.steps), m.wall_time_s = s.wall_time_s;
  if (s.flow) {
    const FlowSummary& f = *s.flow;
    m.flow_steps = static_cast<double>(f.stats.steps), m.flow_ms_per_step = f.ms_per_step;
    m.cells_per_diameter = f.stats.cells_per_diameter, m.flow_dt_s = f.stats.dt;
  }
  return m;
}

/// One scene run reduced-order and, with `flow`, coupled: the reported run's measures and the reduced-order one's.
std::pair<ValidateMeasures, ValidateMeasures> run_scene(const std::string& path, const std::vector<Override>& ov, bool flow) {
  const ValidateMeasures red = measures_of(simulate(load_scene(path, without_flow_keys(ov))).summary);
  if (!flow) return {red, red};
  return {measures_of(simulate(with_flow(path, ov), true).summary), red};
}

/// A Table 6.1 run with a model: its row at V_Io and its row at the speed that gives the printed St_B; or what threw.
struct RowPair {
  ValidateRow at_V, at_St;
  RunFailure failure;
};

void to_json(nlohmann::ordered_json& j, const RowPair& p) { j = {{"at_V", p.at_V}, {"at_St", p.at_St}, {"failure", p.failure}}; }
void from_json(const nlohmann::ordered_json& j, RowPair& p) {
  j.at("at_V").get_to(p.at_V), j.at("at_St").get_to(p.at_St), j.at("failure").get_to(p.failure);
}

/// v with two digits after the point; "n/a" for NaN.
std::string two_digits(double v) {
  if (std::isnan(v)) return "n/a";
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << v;
  return os.str();
}

/// The St_B row: the run at the speed whose St_B(T6.1) is the printed St_B (found by scale_to_St).
void run_at_St(const SeedRun& sr, const Scene& sc, const std::string& path, const std::vector<Override>& ov, bool flow, RowPair& p) {
  const double St_1 = p.at_V.run.St_B_table_6_1;
  if (!(St_1 > 0)) {
    p.at_St.warning = "no St_B at V_Io; its St_B row is the run at V_Io";
    return;
  }
  auto St_at = [&](double scale) {
    auto with_speed = ov;
    for (auto& o : speed_overrides(sc, scale)) with_speed.push_back(o);
    std::tie(p.at_St.run, p.at_St.reduced) = run_scene(path, with_speed, flow);
    p.at_St.V = scale * p.at_V.V;
    const double St = p.at_St.run.St_B_table_6_1;
    return std::isnan(St) ? std::nullopt : std::optional<double>(St);
  };
  scale_to_St(St_1, sr.St_B_value, St_at);
  const double St = p.at_St.run.St_B_table_6_1;
  if (std::isnan(St) || std::abs(St - sr.St_B_value) > 0.01 * sr.St_B_value)
    p.at_St.warning = "St_B(T6.1) " + two_digits(St) + " at the scaled speed, printed " + sr.St_B;
}

/// One Table 6.1 run with one model: its two rows.
RowPair validate_run(const ValidateResult& res, std::size_t seed, std::size_t model, std::vector<Override> ov, bool flow) {
  RowPair p;
  try {
    const SeedRun& sr = res.seeds[seed];
    const std::string path = data_dir() + "/scenes/seed_run" + sr.run + ".toml";
    ov.push_back({"lubrication.model", std::string("\"") + to_string(res.models[model].lubrication) + "\""});  // the model's law
    const Scene sc = load_scene(path, without_flow_keys(ov));
    p.at_V = ValidateRow{};
    p.at_V.seed = seed, p.at_V.model = model, p.at_V.set = SpeedSet::V_Io, p.at_V.V = approach_speed(sc);
    std::tie(p.at_V.run, p.at_V.reduced) = run_scene(path, ov, flow);
    p.at_St = p.at_V;
    p.at_St.set = SpeedSet::St_B;
    run_at_St(sr, sc, path, ov, flow, p);
  } catch (const std::exception&) {
    p.failure = RunFailure::current();
  }
  return p;
}

/// Each model's agreement with the seed's e, per set.
void add_agreement(ValidateResult& res) {
  const std::size_t m = res.models.size();
  res.agreement.assign(2 * m, {});
  res.agreement_reduced.assign(2 * m, {});
  for (const auto& r : res.rows) {
    const std::size_t k = static_cast<std::size_t>(r.set) * m + r.model;
    const SeedRun& sr = res.seed_of(r);
    res.agreement[k].add(sr.run, r.run.e, sr.e_value, res.tolerance);
    if (res.flow) res.agreement_reduced[k].add(sr.run, r.reduced.e, sr.e_value, res.tolerance);
  }
}

}  // namespace validate_runs_impl

ValidateResult validate_seed(const ValidateOptions& opt, const std::vector<Override>& overrides, const Executor& ex, const Hooks& hooks) {
  using namespace validate_runs_impl;
  check_validate_options(opt, overrides);
  ValidateResult res;
  res.flow = opt.flow, res.tolerance = opt.tolerance, res.seeds = read_table_6_1(), res.models = validate_models(opt.models);
  const std::size_t m = res.models.size(), n = res.seeds.size() * m;
  std::vector<RowPair> pairs(n);
  std::vector<char> arrived(n, 0);
  std::vector<std::exception_ptr> thrown(n);  // this process's runs: the exception itself is rethrown
  std::size_t stop = n;
  auto run = [&](std::size_t i) {
    RowPair p = validate_run(res, i / m, i % m, overrides, opt.flow);
    thrown[i] = p.failure.thrown;
    return p;
  };
  auto take = [&](std::size_t i, RowPair&& p) {
    pairs[i] = std::move(p), arrived[i] = 1;
    if (pairs[i].failure.kind == RunFailure::none) return true;
    stop = std::min(stop, i);
    return false;
  };
  run_all<RowPair>(ex, n, run, take, hooks);
  if (!ex.deciding()) return {};
  if (stop < n) {
    pairs[stop].failure.thrown = thrown[stop];
    pairs[stop].failure.rethrow();
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (arrived[i]) res.rows.push_back(pairs[i].at_V);
    else res.cancelled = true;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (arrived[i]) res.rows.push_back(pairs[i].at_St);
  add_agreement(res);
  return res;
}

}  // namespace imcol::study
