// SPDX-License-Identifier: BSD-3-Clause
#include "run/simulate.hpp"

#include <algorithm>
#include <optional>

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
#include "run/summary_json.hpp"
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

/// The effects that ran, the model's choices and the history force's (summary.json's `effects` and `model`).
void put_effects_and_model(RunSummary& s, const CollisionModel& model, const Scene& sc) {
  for (Effect x : sc.effects) s.effects.push_back(x);
  s.model = model.choices();
  if (!sc.has(Effect::history)) return;
  HistorySummary h{sc.history.kernel, sc.history.evaluator, std::nullopt};
  if (model.history(0) && model.history_options().evaluator != HistoryEvaluator::direct) h.modes = static_cast<long>(model.history(0)->modes());
  s.history = h;
  // soe-step: how the memory's outputs inside accepted steps were taken (docs/model-notes.md).
  long interpolated = 0, exact = 0;
  for (std::size_t m = 0; m < model.n_spheres(); ++m)
    if (const auto* hm = model.history(m)) interpolated += hm->interpolated_outputs(), exact += hm->exact_outputs();
  if (interpolated + exact > 0)
    s.model.push_back({"history.outputs", std::to_string(interpolated) + " interpolated, " + std::to_string(exact) + " exact"});
}

/// The events in the order they happened (summary.json's `events`).
std::vector<EventSummary> events_of(const CollisionModel& model) {
  std::vector<EventSummary> ev;
  for (const auto& x : model.events()) ev.push_back({x.t, x.name, x.gap, x.u_rel});
  return ev;
}

/// The `solver` block: settings, tolerances, state names and statistics.
SolverSummary solver_summary(const CollisionModel& model, const IntegratorSettings& st, const SolverStats& stats, double t_final,
                             std::size_t samples) {
  return {st.method, st.rtol, st.atol, model.absolute_tolerances(st.atol), model.component_names(), model.max_step_outside_contact(),
          t_final, st.output_dt, samples, stats};
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

namespace {

/// What one integration gave: the model's statistics and the flow kernel's (coupled runs), and the wall time.
struct Integration {
  SolverStats stats;
  std::optional<coupling::FlowRunStats> flow;
  double wall = 0;
};

/// The spheres' path in trajectory rows: t, and z_m, u_m from the columns "z1", "u1" (and "z2", "u2").
coupling::ExpectedRun path_of(const RunResult& r, std::size_t spheres) {
  coupling::ExpectedRun e;
  auto column = [&](const std::string& name) {
    const auto it = std::find(r.columns.begin(), r.columns.end(), name);
    return it == r.columns.end() ? std::string::npos : static_cast<std::size_t>(it - r.columns.begin());
  };
  std::array<std::size_t, 2> zc{}, uc{};
  for (std::size_t m = 0; m < spheres; ++m) {
    const std::string k = std::to_string(m + 1);
    zc[m] = column(std::string("z").append(k));
    uc[m] = column(std::string("u").append(k));
    if (zc[m] == std::string::npos || uc[m] == std::string::npos) return e;
  }
  for (const auto& row : r.rows) {
    e.t.push_back(row[0]);
    std::array<double, 2> z{}, u{};
    for (std::size_t m = 0; m < spheres; ++m) z[m] = row[zc[m]], u[m] = row[uc[m]];
    e.z.push_back(z);
    e.u.push_back(u);
  }
  return e;
}

/// How a coupled run will likely go: the reduced-order model's own run (its end: at rest, separated and measured, or
/// t_end; and its path), a run of milliseconds; t_end and no path if it fails.
coupling::ExpectedRun expected_run(const Scene& sc) {
  Scene reduced = sc;
  reduced.effects.erase(Effect::flow);
  try {
    const RunResult r = simulate(reduced, false, Recording::kinematics, {});
    coupling::ExpectedRun e = path_of(r, sc.spheres.size());
    e.end = r.summary.solver.t_final_s;
    if (r.summary.contact) {
      e.t_contact = r.summary.contact->t_contact_s;
      e.t_separation = r.summary.contact->t_separation_s;
    }
    return e;
  } catch (const std::exception&) {
    coupling::ExpectedRun e;
    e.end = sc.solver.t_end;
    return e;
  }
}

/// Integrates the model alone, or coupled to the flow kernel, into the recorder.
Integration integrate_run(CollisionModel& model, const Scene& sc, const IntegratorSettings& st, run::Recorder& rec, bool progress,
                          const flow::FileSink& fields) {
  const auto wall_start = WallClock::now();
  Integration out;
  try {
    if (sc.has(Effect::flow)) {
      coupling::FlowCoupling coupled(model, sc);
      if (progress) coupled.set_progress([&rec](const std::string& text) { rec.show_status(text); });
      if (fields) coupled.set_file_sink(fields);
      coupled.set_expected_run(expected_run(sc));
      out.stats = coupled.run(st, rec);
      out.flow = coupled.stats();
    } else {
      out.stats = integrate(model, st, rec);
    }
  } catch (...) {
    rec.finish_progress();
    throw;
  }
  rec.finish_progress();
  out.wall = seconds_since(wall_start);
  return out;
}

/// The measures and the summary of an integrated run.
RunSummary summarize(const CollisionModel& model, const run::Watch& watch, const Scene& sc, const run::Recorder& rec,
                     const std::vector<std::vector<double>>& rows, const IntegratorSettings& st, const Integration& in) {
  // Measure: the first contact as the seed does, then every contact with each named measure.
  std::vector<std::string> warnings;
  run::FirstContact first = run::measure_first_contact(model, watch, sc, rec.track(), warnings);
  std::vector<run::Bounce> bounces;
  if (model.has_target() && sc.has(Effect::elastic) && !rec.track().t.empty())
    bounces = run::measure_bounces(model, watch, sc, rec.track(), warnings);
  run::choose_e(sc, bounces, first, warnings);
  run::check_plausibility(model, sc, first, warnings);

  RunSummary s;
  s.scene = sc.name;
  s.scene_file = sc.path;
  s.configuration = !model.has_target() ? Configuration::free_sphere
                                        : (model.has_wall() ? Configuration::sphere_wall : Configuration::sphere_sphere);
  s.fluid = sc.fluid;
  run::measure_summary(s, model, watch, sc, first, std::move(bounces), rec, rows);
  if (model.has_target() && sc.has(Effect::elastic)) s.contact = run::contact_summary(model);
  put_effects_and_model(s, model, sc);
  s.solver = solver_summary(model, st, in.stats, rows.empty() ? 0.0 : rows.back()[0], rec.track().t.size());
  s.events = events_of(model);
  s.warnings = warnings;
  if (in.flow) s.flow = run::flow_summary(*in.flow, sc, in.wall);
  s.wall_time_s = in.wall;
  return s;
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

  // The integrator samples at the measures' own interval; the recorder keeps rows every output.dt.
  IntegratorSettings st = integrator_settings(sc);
  st.output_dt = run::measure_interval(model, sc);
  run::Recorder rec(model, sc, progress, recording == Recording::full, st.output_dt);
  const Integration in = integrate_run(model, sc, st, rec, progress, fields);

  RunResult res;
  res.scene = sc;
  res.columns = rec.columns();
  res.rows = std::move(rec.rows());
  res.contact_rows = std::move(rec.contact_rows());
  res.summary = summarize(model, watch, sc, rec, res.rows, st, in);
  res.summary.setup_time_s = setup;  // model construction, incl. one-off lookup tables
  res.summary_json = res.summary;    // summary.json, written from the typed summary alone
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
