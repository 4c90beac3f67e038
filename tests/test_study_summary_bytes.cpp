// SPDX-License-Identifier: BSD-3-Clause
// study/point_json.hpp and run/summary_json.hpp: a real run's RunSummary, a sweep point and a history cell cross ranks
// as CBOR bytes of their JSON (summary.json's object for the summary) and come back equal field for field, every
// double to the bit (-0 and NaN too).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/scene.hpp"
#include "core/scene_files.hpp"
#include "run/simulate.hpp"
#include "run/summary.hpp"
#include "study/history_sweep.hpp"
#include "study/run_all.hpp"
#include "study/point_json.hpp"

namespace imcol::study {
namespace {

bool bits_equal(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_bits(const std::optional<double>& a, const std::optional<double>& b, const char* what) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) {
    EXPECT_TRUE(bits_equal(*a, *b)) << what << ": " << *a << " vs " << *b;
  }
}

void expect_same_stats(const SolverStats& a, const SolverStats& b) {
  EXPECT_EQ(a.as_map(), b.as_map());
  EXPECT_EQ(a.linear_solver, b.linear_solver);
  EXPECT_EQ(a.state_size, b.state_size);
}

void expect_same_contact(const std::optional<ContactSummary>& a, const std::optional<ContactSummary>& b) {
  ASSERT_EQ(a.has_value(), b.has_value());
  if (!a) return;
  EXPECT_EQ(a->law, b->law);
  expect_bits(a->t_contact_s, b->t_contact_s, "t_contact_s");
  expect_bits(a->t_separation_s, b->t_separation_s, "t_separation_s");
  expect_bits(a->impact_speed_m_s, b->impact_speed_m_s, "impact_speed_m_s");
  ASSERT_EQ(a->law_numbers.size(), b->law_numbers.size());
  for (std::size_t k = 0; k < a->law_numbers.size(); ++k) {
    EXPECT_EQ(a->law_numbers[k].first, b->law_numbers[k].first);
    expect_bits(a->law_numbers[k].second, b->law_numbers[k].second, "law number");
  }
  EXPECT_TRUE(bits_equal(a->e_dry, b->e_dry));
  EXPECT_TRUE(bits_equal(a->delta_ss_m, b->delta_ss_m));
}

void expect_same_bounces(const std::vector<run::Bounce>& a, const std::vector<run::Bounce>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].contact, b[k].contact);
    EXPECT_TRUE(bits_equal(a[k].t_contact_s, b[k].t_contact_s));
    for (auto m : {&run::Bounce::t_separation_s, &run::Bounce::e, &run::Bounce::impact_velocity_m_s, &run::Bounce::rebound_velocity_m_s,
                   &run::Bounce::e_instant, &run::Bounce::apex_gap_m, &run::Bounce::t_apex_s})
      expect_bits(a[k].*m, b[k].*m, "bounce");
  }
}

void expect_same_summary(const RunSummary& a, const RunSummary& b) {
  EXPECT_EQ(a.scene, b.scene);
  EXPECT_EQ(a.scene_file, b.scene_file);
  EXPECT_EQ(a.configuration, b.configuration);
  ASSERT_EQ(a.fluid.has_value(), b.fluid.has_value());
  if (a.fluid) {
    EXPECT_TRUE(bits_equal(a.fluid->viscosity, b.fluid->viscosity) && bits_equal(a.fluid->density, b.fluid->density));
    EXPECT_EQ(a.fluid->name, b.fluid->name);
    EXPECT_EQ(a.fluid->viscosity_source, b.fluid->viscosity_source);
  }
  using O = std::optional<double> RunSummary::*;
  for (O m : {&RunSummary::e, &RunSummary::e_fit_raw, &RunSummary::e_instant, &RunSummary::energy_closure, &RunSummary::St,
              &RunSummary::St_B_table_6_1, &RunSummary::St_B_eq_6_2, &RunSummary::St_L, &RunSummary::St_initial, &RunSummary::Re,
              &RunSummary::at_rest_since_s, &RunSummary::U_i1, &RunSummary::U_i2, &RunSummary::U_r1, &RunSummary::U_r2,
              &RunSummary::min_gap_m, &RunSummary::max_contact_force_N, &RunSummary::max_history_force_N, &RunSummary::group_velocity_m_s,
              &RunSummary::group_velocity_at_s, &RunSummary::u1_final_m_s, &RunSummary::u2_final_m_s})
    expect_bits(a.*m, b.*m, "summary");
  EXPECT_EQ(a.e_is, b.e_is);
  EXPECT_EQ(a.e_missing, b.e_missing);
  EXPECT_TRUE(bits_equal(a.e_instant_gap_m, b.e_instant_gap_m));
  ASSERT_EQ(a.e_measures.size(), b.e_measures.size());
  for (std::size_t k = 0; k < a.e_measures.size(); ++k) {
    EXPECT_EQ(a.e_measures[k].first, b.e_measures[k].first);
    expect_bits(a.e_measures[k].second, b.e_measures[k].second, "e_measures");
  }
  // e_by_measure is the printed line's text, not part of summary.json: it does not cross.
  EXPECT_EQ(a.dissipated_share, b.dissipated_share);
  EXPECT_EQ(a.measures_disagree, b.measures_disagree);
  EXPECT_EQ(a.bounces_mode, b.bounces_mode);
  expect_same_bounces(a.bounces, b.bounces);
  EXPECT_EQ(a.St_convention, b.St_convention);
  EXPECT_EQ(a.separated, b.separated);
  EXPECT_EQ(a.t_end_too_short, b.t_end_too_short);
  EXPECT_EQ(a.final_phase, b.final_phase);
  EXPECT_EQ(a.contacts, b.contacts);
  EXPECT_TRUE(bits_equal(a.fit_window_s, b.fit_window_s));
  expect_same_contact(a.contact, b.contact);
  EXPECT_EQ(a.effects, b.effects);
  EXPECT_EQ(a.model, b.model);
  ASSERT_EQ(a.history.has_value(), b.history.has_value());
  if (a.history) {
    EXPECT_EQ(a.history->kernel, b.history->kernel);
    EXPECT_EQ(a.history->evaluator, b.history->evaluator);
    EXPECT_EQ(a.history->modes, b.history->modes);
  }
  EXPECT_EQ(a.solver.integrator, b.solver.integrator);
  for (auto m : {&SolverSummary::rtol, &SolverSummary::atol, &SolverSummary::t_final_s, &SolverSummary::measure_interval_s})
    EXPECT_TRUE(bits_equal(a.solver.*m, b.solver.*m));
  EXPECT_EQ(a.solver.measure_samples, b.solver.measure_samples);
  expect_same_stats(a.solver.stats, b.solver.stats);
  EXPECT_EQ(a.flow.has_value(), b.flow.has_value());
  EXPECT_EQ(a.warnings, b.warnings);
  EXPECT_TRUE(bits_equal(a.wall_time_s, b.wall_time_s) && bits_equal(a.setup_time_s, b.setup_time_s));
}

/// A finished run of a shipped scene with history, a contact and the energy budget (full recording).
RunSummary real_summary() { return simulate(load_scene(find_scene("default"))).summary; }

TEST(StudySummaryBytes, ARealRunSummaryRoundTripsFieldForField) {
  const RunSummary a = real_summary();
  ASSERT_TRUE(a.e && a.contact && !a.e_measures.empty() && !a.bounces.empty() && a.fluid);
  const RunSummary b = from_bytes<RunSummary>(to_bytes(a));
  expect_same_summary(a, b);
  // What summary.json makes of them: the same bytes.
  EXPECT_EQ(run::Json(a).dump(), run::Json(b).dump());
}

TEST(StudySummaryBytes, DoublesKeepEveryBitAcrossTheBytes) {
  RunSummary a;
  a.e = -0.0;
  a.U_i1 = 0.1 + 0.2;  // not a float: stored as a double
  a.U_i2 = 0.5;        // a float: CBOR's shorter form, exact
  a.Re = 1e-300;
  a.flow.emplace();
  a.flow->stats.dt = 1.0 / 3.0;
  const RunSummary b = from_bytes<RunSummary>(to_bytes(a));
  expect_same_summary(a, b);
  EXPECT_TRUE(std::signbit(*b.e));
  ASSERT_TRUE(b.flow);
  EXPECT_TRUE(bits_equal(b.flow->stats.dt, 1.0 / 3.0));
  // CBOR has NaN (JSON text has not: summary.json writes null there).
  a.St = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(from_bytes<RunSummary>(to_bytes(a)).St.value_or(0)));
}

TEST(StudySummaryBytes, ASweepPointAndAHistoryCellRoundTrip) {
  SweepPoint p;
  p.ok = true;
  p.value = 0.123456789012345;
  p.summary = real_summary();
  p.message = "t_end extended to 0.02 s";
  const SweepPoint q = from_bytes<SweepPoint>(to_bytes(p));
  EXPECT_EQ(q.ok, p.ok);
  EXPECT_TRUE(bits_equal(q.value, p.value));
  EXPECT_EQ(q.message, p.message);
  expect_same_summary(p.summary, q.summary);

  HistoryCell c;
  c.point = 3;
  c.value = 2.5e-3;
  c.series = {"mei", "soe"};
  c.status = "failed";
  c.message = "CVODE failed";
  const HistoryCell d = from_bytes<HistoryCell>(to_bytes(c));
  EXPECT_EQ(d.point, 3);
  EXPECT_TRUE(bits_equal(d.value, c.value));
  EXPECT_EQ(d.series.name(), "mei soe");
  EXPECT_EQ(d.status, "failed");
  EXPECT_EQ(d.message, c.message);
}

}  // namespace
}  // namespace imcol::study
