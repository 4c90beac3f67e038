// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// summary.json of a collision run, block by block, and the short text `imcol run` prints.
#include <nlohmann/json.hpp>
#include <string>

#include "model/collision_model.hpp"
#include "core/scene.hpp"
#include "coupling/flow_coupling.hpp"
#include "integrators/integrator.hpp"
#include "run/first_contact.hpp"
#include "run/recorder.hpp"
#include "run/run_summary.hpp"
#include "run/watch.hpp"

namespace imcol::run {

/// e, e_instant, the named measures, St, Re, velocities, group velocity, contact extremes: the measurements, into
/// `s` (`bounces`: measure_bounces' contacts).
void measure_summary(RunSummary& s, const model::CollisionModel& model, const Watch& watch, const Scene& sc, const FirstContact& m,
                     const nlohmann::ordered_json& bounces, const Recorder& rec, const std::vector<std::vector<double>>& rows);

/// The measurements of `s` (measure_summary) into summary.json's object `j`.
void put_measurements(nlohmann::ordered_json& j, const RunSummary& s, const Scene& sc, const nlohmann::ordered_json& bounces);

/// The `contact` block's values: the law, times, impact speed, the law's numbers (ramp: W_o, β), e_dry, δ_SS.
ContactSummary contact_summary(const model::CollisionModel& model);
nlohmann::ordered_json contact_block(const ContactSummary& c);

/// The `solver` block: settings, tolerances, state names and statistics.
nlohmann::ordered_json solver_block(const model::CollisionModel& model, const IntegratorSettings& st, const SolverStats& stats,
                                    double t_final);

/// The `flow` block of a coupled run: grid, step, Krylov statistics, wall-time shares (`wall`: the run's, s).
FlowSummary flow_summary(const coupling::FlowRunStats& fs, const Scene& sc, double wall);
nlohmann::ordered_json flow_block(const FlowSummary& f);

/// The `fluid` block: name, mass fraction, temperature (°C), density, viscosity and the source of each value.
nlohmann::ordered_json fluid_block(const FluidSpec& f);
/// One line on the liquid: "fluid: glycerol-water, w = 0.5, 20 °C: rho = 1126.1 kg/m3 (Volk & Kähler (2018)), mu = ..."
std::string fluid_line(const FluidSpec& f);

/// What `imcol run` prints.
std::string human_summary(const RunSummary& s);

}  // namespace imcol::run
