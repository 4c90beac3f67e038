// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A collision run's summary (run/run_summary.hpp) from the model and the measures, block by block, and the short text
// `imcol run` prints. summary.json is written from it by run/summary_json.hpp.
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
/// `s` (`bounces`: measure_bounces' contacts, moved into s).
void measure_summary(RunSummary& s, const model::CollisionModel& model, const Watch& watch, const Scene& sc, const FirstContact& m,
                     std::vector<Bounce> bounces, const Recorder& rec, const std::vector<std::vector<double>>& rows);

/// The `contact` block's values: the law, times, impact speed, the law's numbers (ramp: W_o, β), e_dry, δ_SS.
ContactSummary contact_summary(const model::CollisionModel& model);

/// The `flow` block of a coupled run: grid, step, Krylov statistics, wall-time shares (`wall`: the run's, s).
FlowSummary flow_summary(const coupling::FlowRunStats& fs, const Scene& sc, double wall);

/// One line on the liquid: "fluid: glycerol-water, w = 0.5, 20 °C: rho = 1126.1 kg/m3 (Volk & Kähler (2018)), mu = ..."
std::string fluid_line(const FluidSpec& f);
/// The text summary's flow line: grid, steps (the adaptive range), cost per step, shares of the wall time (s).
std::string flow_line(const FlowSummary& f, double wall_time_s);

/// What `imcol run` prints.
std::string human_summary(const RunSummary& s);

}  // namespace imcol::run
