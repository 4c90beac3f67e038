// SPDX-License-Identifier: BSD-3-Clause
// study/sweep.hpp and study/laws.hpp on this process's threads: every point taken once through the typed callback,
// a cancelled study returns what finished with its flag set, and the tables keep the commands' columns.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/scene_files.hpp"
#include "study/laws.hpp"
#include "study/sweep.hpp"
#include "study/sweep_columns.hpp"

namespace imcol::study {
namespace {

/// The shipped scene `default` at `values` of its impact velocity, every point's scene checked.
std::vector<Scene> default_velocity_scenes(const std::vector<double>& values) {
  const std::string path = find_scene("default");
  return sweep_scenes(path, {}, load_scene(path), "velocity", values);
}

TEST(StudySweep, EveryPointTakenOnceInTheResultWithProgress) {
  const std::vector<double> values = {0.2, 0.4, 0.6, 0.8};
  std::vector<int> taken(values.size(), 0);
  std::size_t last_progress = 0;
  Hooks hooks;
  hooks.progress = [&](std::size_t done, std::size_t total) {
    EXPECT_EQ(total, values.size());
    last_progress = done;
  };
  const SweepResult r = run_sweep(default_velocity_scenes(values), "velocity", values, threads(2), hooks,
                                  [&](std::size_t i, const SweepResult& so_far) {
                                    EXPECT_TRUE(so_far.done[i]);
                                    ++taken[i];
                                    return true;
                                  });
  EXPECT_FALSE(r.cancelled);
  EXPECT_EQ(r.finished(), values.size());
  EXPECT_EQ(r.failed(), 0u);
  EXPECT_EQ(last_progress, values.size());
  EXPECT_EQ(r.column, "velocity_m_s");
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(taken[i], 1);
    EXPECT_TRUE(r.points[i].ok) << r.points[i].message;
    EXPECT_EQ(r.points[i].value, values[i]);
    ASSERT_TRUE(r.points[i].summary.e);
  }
  EXPECT_LT(*r.points[0].summary.e, *r.points[3].summary.e);  // e grows with St
}

TEST(StudySweep, ACancelledSweepReturnsWhatFinished) {
  const std::vector<double> values = {0.2, 0.3, 0.4, 0.5, 0.6};
  std::size_t taken = 0;
  Hooks hooks;
  hooks.cancelled = [&] { return taken >= 2; };
  const SweepResult r = run_sweep(default_velocity_scenes(values), "velocity", values, threads(1), hooks,
                                  [&](std::size_t, const SweepResult&) { return ++taken, true; });
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(r.finished(), 2u);
  EXPECT_TRUE(r.done[0] && r.done[1] && !r.done[2]);
  EXPECT_TRUE(std::isnan(sweep_columns()[0].number(r.points[2]).value_or(NAN)));  // a point not run has no St
}

TEST(StudyLaws, TheTableHasLawsCsvColumnsAndACancelStopsTheRuns) {
  const std::string path = find_scene("default");
  const SceneLoader load = [&](const std::vector<Override>& ov) { return load_scene(path, ov); };
  const LawsResult r = compare_laws(load, {}, {"ramp", "hertz"}, "", {});
  ASSERT_EQ(r.rows.size(), 2u);
  ASSERT_GE(r.first_ran, 0);
  const Table t = laws_table(r);
  EXPECT_EQ(t.rows, 2u);
  EXPECT_EQ(t.columns.front().name, "law");
  EXPECT_EQ(t.columns.back().name, "message");
  EXPECT_EQ(t.columns[1].text, (std::vector<std::string>{"ran", "ran"}));
  EXPECT_EQ(t.columns[2].name, "e");
  EXPECT_EQ(t.columns[2].numbers[0], *r.rows[0].run.summary.e);
  EXPECT_EQ(t.columns[3].name, "e_minus_e_ramp");
  EXPECT_EQ(t.columns[3].numbers[0], 0.0);  // the ramp against itself

  Hooks hooks;
  hooks.cancelled = [] { return true; };
  const LawsResult none = compare_laws(load, {}, {"ramp", "hertz"}, "velocity", {0.2, 0.4}, false, hooks);
  EXPECT_TRUE(none.cancelled);
  EXPECT_TRUE(none.rows.empty());
  EXPECT_EQ(none.column, "velocity_m_s");
}

}  // namespace
}  // namespace imcol::study
