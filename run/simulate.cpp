// SPDX-License-Identifier: BSD-3-Clause
#include "run/simulate.hpp"

#include <algorithm>
#include <memory>

#include "model/approach.hpp"
#include "model/collision_model.hpp"
#include "core/errors.hpp"
#include "core/number_text.hpp"
#include "core/report.hpp"
#include "core/timing.hpp"
#include "coupling/flow_coupling.hpp"
#include "integrators/integrator.hpp"
#include "run/bounces.hpp"
#include "run/first_contact.hpp"
#include "run/recorder.hpp"
#include "run/summary.hpp"
#include "run/watch.hpp"

namespace imcol {

namespace {

using model::CollisionModel;

IntegratorSettings integrator_settings(const Scene& sc) {
  IntegratorSettings st;
  st.method = sc.solver.integrator;
  st.rtol = sc.solver.rtol;
  st.atol = sc.solver.atol;
  st.output_dt = sc.output.dt;
  st.max_steps = sc.solver.max_steps;
  st.linear_solver = sc.solver.linear_solver;
  st.krylov_tol = sc.solver.krylov_tol;
  return st;
}

/// The effects that ran and the model's choices (summary.json's `effects` and `model`).
void put_effects_and_model(RunSummary& s, nlohmann::ordered_json& j, const CollisionModel& model, const Scene& sc) {
  for (Effect x : sc.effects) s.effects.push_back(to_string(x));
  j["effects"] = s.effects;
  s.model = model.choices();
  nlohmann::ordered_json mod = nlohmann::ordered_json::object();
  for (const auto& [k, v] : s.model) mod[k] = v;
  j["model"] = mod;
  if (model.history(0) && model.history_options().evaluator != HistoryEvaluator::direct)
    s.history_modes = static_cast<long>(model.history(0)->modes());
}

/// The events in the order they happened (summary.json's `events`).
nlohmann::ordered_json events_block(const CollisionModel& model) {
  nlohmann::ordered_json ev = nlohmann::ordered_json::array();
  for (const auto& x : model.events()) ev.push_back({{"t", x.t}, {"event", x.name}, {"gap_m", x.gap}, {"u_rel_m_s", x.u_rel}});
  return ev;
}

/// The scene a run integrates: `scene`, or for a kinematic recording (e alone: sweeps, calibrations) its copy in `lean`
/// without the energy budget.
const Scene& scene_to_run(const Scene& scene, Recording recording, Scene& lean) {
  if (recording != Recording::kinematics || !scene.measure.energy_budget) return scene;
  lean = scene;
  lean.measure.energy_budget = false;
  return lean;
}

}  // namespace

RunResult simulate(const Scene& scene, bool progress, Recording recording, const flow::FileSink& fields) {
  Scene lean;
  const Scene& sc = scene_to_run(scene, recording, lean);
  // A scene that can never collide is refused before anything is integrated: its trajectory would be the whole
  // run to t_end with nothing to measure.
  if (const auto why = model::never_approaching(sc)) throw InputError(sc.path, "sphere[0].velocity", *why);
  const auto setup_start = WallClock::now();
  CollisionModel model(sc);
  run::Watch watch(model, sc);  // not const: the model updates its watchers
  const double setup = seconds_since(setup_start);

  // Integrate: the reduced-order model alone, or coupled to the flow kernel.
  const auto wall_start = WallClock::now();
  // The integrator samples at the measures' own interval; the recorder keeps rows every output.dt.
  IntegratorSettings st = integrator_settings(sc);
  st.output_dt = run::measure_interval(model, sc);
  run::Recorder rec(model, sc, progress, recording == Recording::full, st.output_dt);
  std::unique_ptr<coupling::FlowCoupling> coupled;
  SolverStats stats;
  try {
    if (sc.has(Effect::flow)) {
      coupled = std::make_unique<coupling::FlowCoupling>(model, sc);
      if (progress) coupled->set_progress([&rec](const std::string& text) { rec.show_status(text); });
      if (fields) coupled->set_file_sink(fields);
      stats = coupled->run(st, rec);
    } else {
      stats = integrate(model, st, rec);
    }
  } catch (...) {
    rec.finish_progress();
    throw;
  }
  rec.finish_progress();
  const double wall = seconds_since(wall_start);

  RunResult res;
  res.scene = sc;
  res.columns = rec.columns();
  res.rows = std::move(rec.rows());
  res.contact_rows = std::move(rec.contact_rows());
  const double t_final = res.rows.empty() ? 0.0 : res.rows.back()[0];

  // Measure: the first contact as the seed does, then every contact with each named measure.
  std::vector<std::string> warnings;
  run::FirstContact first = run::measure_first_contact(model, watch, sc, rec.track(), warnings);
  nlohmann::ordered_json bounces = nlohmann::ordered_json::array();
  if (model.has_target() && sc.has(Effect::elastic) && !rec.track().t.empty())
    bounces = run::measure_bounces(model, watch, sc, rec.track(), warnings);
  run::choose_e(sc, bounces, first, warnings);
  run::check_plausibility(model, sc, first, warnings);

  // Report: the typed summary, and summary.json from the same values.
  RunSummary& s = res.summary;
  auto& j = res.summary_json;
  s.scene = sc.name;
  s.scene_file = sc.path;
  s.configuration = !model.has_target() ? Configuration::free_sphere
                                        : (model.has_wall() ? Configuration::sphere_wall : Configuration::sphere_sphere);
  run::measure_summary(s, model, watch, sc, first, bounces, rec, res.rows);
  j["scene"] = s.scene;
  j["scene_file"] = s.scene_file;
  j["configuration"] = to_string(s.configuration);
  s.fluid = sc.fluid;
  if (s.fluid) j["fluid"] = run::fluid_block(*s.fluid);
  run::put_measurements(j, s, sc, bounces);
  if (model.has_target() && sc.has(Effect::elastic)) {
    s.contact = run::contact_summary(model);
    j["contact"] = run::contact_block(*s.contact);
  }
  put_effects_and_model(s, j, model, sc);
  s.solver = {to_string(st.method), st.rtol, st.atol, t_final, st.output_dt, rec.track().t.size(), stats};
  j["solver"] = run::solver_block(model, st, stats, t_final);
  j["solver"]["measure_interval_s"] = s.solver.measure_interval_s;  // the integrator's sampling, which the measures read
  j["solver"]["measure_samples"] = s.solver.measure_samples;
  j["events"] = events_block(model);
  s.warnings = warnings;
  j["warnings"] = s.warnings;
  if (coupled) {
    s.flow = run::flow_summary(coupled->stats(), sc, wall);
    j["flow"] = run::flow_block(*s.flow);
  }
  s.wall_time_s = wall;
  s.setup_time_s = setup;  // model construction, incl. one-off lookup tables
  j["wall_time_s"] = s.wall_time_s;
  j["setup_time_s"] = s.setup_time_s;
  return res;
}

void write_outputs(const RunResult& r, const std::filesystem::path& dir) {
  std::string csv;
  for (std::size_t i = 0; i < r.columns.size(); ++i) csv += (i ? "," : "") + r.columns[i];
  csv += '\n';
  csv.reserve(csv.size() + r.rows.size() * r.columns.size() * 12);
  for (const auto& row : r.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i) csv += ',';
      append_number(csv, row[i], 12);
    }
    csv += '\n';
  }
  write_file_atomic(dir / "trajectory.csv", csv);
  write_file_atomic(dir / "summary.json", r.summary_json.dump(2) + "\n");
}

std::string human_summary(const RunResult& r) { return run::human_summary(r.summary); }

}  // namespace imcol
