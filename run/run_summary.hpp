// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The results of a collision run as typed values: what the commands, the studies, the benchmarks and Python read.
// summary.json is written from them alone (run/summary_json.hpp), under the same names; absent and null there are
// std::nullopt here. Units: SI (m, s, m/s, N, J).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/scene.hpp"
#include "coupling/flow_run_stats.hpp"
#include "integrators/integrator.hpp"
#include "run/bounce.hpp"

namespace imcol {

enum class Configuration { free_sphere, sphere_wall, sphere_sphere };
/// "free sphere", "sphere-wall", "sphere-sphere" (summary.json `configuration`).
const char* to_string(Configuration c);

/// The `contact` block: the law and the first contact's times and impact speed; the law's own numbers by name.
struct ContactSummary {
  ContactLawKind law = ContactLawKind::ramp;
  std::optional<double> t_contact_s, t_separation_s, impact_speed_m_s;
  std::vector<std::pair<std::string, std::optional<double>>> law_numbers;
  double e_dry = 1, delta_ss_m = 0;
};

/// The `flow` block of a coupled run: the kernel's statistics and what is derived from them.
struct FlowSummary {
  coupling::FlowRunStats stats;
  FlowStart start = FlowStart::impulsive;  // flow.start
  ForceInStep force_in_step = ForceInStep::linear;  // flow.force_in_step
  double ms_per_step = 0;                 // kernel wall time per coupled step
  double krylov_iterations_per_step = 0;
  double flow_share = 0, ode_share = 0;   // of the run's wall time
};

/// The `solver` block's settings and statistics.
struct SolverSummary {
  IntegratorMethod integrator = IntegratorMethod::cvode;
  double rtol = 0, atol = 0;
  std::vector<double> absolute_tolerances;  // per state component
  std::vector<std::string> state;           // the state components' names
  double max_step_s = 0;                    // the step bound outside contact
  double t_final_s = 0;
  double measure_interval_s = 0;  // the integrator's sampling, which the measures read
  std::size_t measure_samples = 0;
  SolverStats stats;
};

/// One event of the run (summary.json `events`), in the order they happened.
struct EventSummary {
  double t_s = 0;
  std::string event;  // what happened, e.g. "gap=delta_ss (in)"
  double gap_m = 0, u_rel_m_s = 0;
};

/// The history force's kernel and evaluator, and its exponentials (soe evaluators).
struct HistorySummary {
  KernelKind kernel = KernelKind::basset;
  HistoryEvaluator evaluator = HistoryEvaluator::soe_step;
  std::optional<long> modes;
};

struct RunSummary {
  std::string scene, scene_file;
  Configuration configuration = Configuration::free_sphere;
  std::optional<FluidSpec> fluid;  // the liquid's values used and where each came from (none: dry)

  // e and its measures (docs/bounces.md)
  std::optional<double> e;
  EMeasure e_is = EMeasure::contact_ends;  // the named measure e is (measure.e)
  std::optional<std::string> e_missing;    // why e is undefined (only without e; may be unknown)
  std::optional<double> e_fit_raw, e_instant;
  double e_instant_gap_m = 0;
  /// The first contact's named measures, measure → e (empty without a contact), in summary.json's order.
  std::vector<std::pair<EMeasure, std::optional<double>>> e_measures;
  std::optional<std::string> e_by_measure;  // one printed line: e by each distinct measure and their spread (not in summary.json)
  /// The first collision's energy budget over approach, contact and rebound (run/energy_budget.hpp), and from it what
  /// each force dissipated (above 5e-4), in units of the impact kinetic energy, and the largest |closure| of a phase.
  std::optional<run::EnergyBudget> energy_budget;
  std::vector<std::pair<model::ForceKind, double>> dissipated_share;
  std::optional<double> energy_closure;
  /// The distinct measures whose e differs from e by more than measure.disagreement, label → e.
  std::vector<std::pair<std::string, double>> measures_disagree;
  BouncesMode bounces_mode = BouncesMode::first;  // measure.bounces
  std::vector<run::Bounce> bounces;

  // Dimensionless numbers at impact (the conventions: summary.json St_convention, docs/model-notes.md)
  std::optional<double> St, St_B_table_6_1, St_B_eq_6_2, St_L, St_initial, Re;
  std::string St_convention;

  // How the run went
  bool separated = false, t_end_too_short = false;
  std::optional<double> at_rest_since_s;
  std::optional<std::string> final_phase;
  int contacts = 0;
  std::optional<double> U_i1, U_i2, U_r1, U_r2;  // fitted impact and rebound velocities, m/s
  double fit_window_s = 0;
  std::optional<double> min_gap_m, max_contact_force_N, max_history_force_N;
  std::optional<double> group_velocity_m_s, group_velocity_at_s;
  std::optional<double> u1_final_m_s, u2_final_m_s;
  std::optional<ContactSummary> contact;  // a target and the elastic effect

  std::vector<Effect> effects;
  std::vector<std::pair<std::string, std::string>> model;  // the model's choices, for display (summary.json `model`)
  std::optional<HistorySummary> history;                   // with the history effect
  SolverSummary solver;
  std::vector<EventSummary> events;
  std::optional<FlowSummary> flow;  // coupled runs
  std::vector<std::string> warnings;
  double wall_time_s = 0;   // integration and measures
  double setup_time_s = 0;  // model construction, incl. one-off lookup tables

  /// e of named measure `m` at the first contact; nullopt when not measured or without a contact.
  std::optional<double> measure_e(EMeasure m) const;
  bool has(Effect x) const;
};

/// The first contact's views in s, from s.bounces[0]: e_measures, measures_disagree, energy_budget, and from the
/// budget dissipated_share and energy_closure (all empty without a contact).
void first_contact_views(RunSummary& s);

}  // namespace imcol
