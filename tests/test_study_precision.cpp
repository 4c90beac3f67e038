// SPDX-License-Identifier: BSD-3-Clause
// study/work_precision.hpp and study/validate.hpp: rows that cross ranks as bytes equal those run on threads bit for
// bit; a solver failure fails its rung alone; cancellation keeps the rungs that finished; a bad option is refused.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/scene.hpp"
#include "core/scene_files.hpp"
#include "run/summary_json.hpp"
#include "study//run_all.hpp"
#include "study/validate.hpp"
#include "study/work_precision.hpp"

namespace imcol::study {
namespace {

/// Two ranks in this process: every result passes through its bytes, as over MPI.
Executor precision_two_ranks() {
  Executor ex = threads(1);
  ex.ranks = 2;
  ex.distribute = [](std::size_t n, int jobs, const std::function<std::string(std::size_t)>& work,
                     const std::function<bool(std::size_t, std::string, int)>& done) {
    run_parallel(n, jobs, work, [&](std::size_t i, std::string b) { return done(i, std::move(b), 1); });
  };
  return ex;
}

WorkPrecisionPlan precision_plan(const std::string& scene, std::vector<Override> ov, WorkPrecisionOptions opt) {
  return plan_work_precision(load_scene(find_scene(scene), ov), opt);
}

WorkPrecisionOptions precision_options(std::vector<double> rtols, std::vector<std::string> integrators, std::vector<std::string> evaluators) {
  WorkPrecisionOptions opt;
  opt.rtols = std::move(rtols), opt.integrators = std::move(integrators), opt.evaluators = std::move(evaluators);
  opt.repeat = 1;
  return opt;
}

TEST(StudyWorkPrecision, RowsAcrossRanksEqualRowsOnThreads) {
  const auto plan = precision_plan("default", {}, precision_options({1e-4, 1e-6}, {"cvode-dense", "ida"}, {"soe"}));
  const WorkPrecisionResult a = work_precision(plan, threads(2));
  const WorkPrecisionResult b = work_precision(plan, precision_two_ranks());
  ASSERT_EQ(a.rows.size(), 4u);
  ASSERT_EQ(b.rows.size(), 4u);
  EXPECT_EQ(a.value, b.value);
  EXPECT_EQ(a.uncertainty, b.uncertainty);
  EXPECT_EQ(run::Json(a.solver).dump(), run::Json(b.solver).dump());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_TRUE(a.rows[i].ok);
    EXPECT_EQ(a.rows[i].cfg.label(), b.rows[i].cfg.label());
    EXPECT_EQ(a.rows[i].e, b.rows[i].e);
    EXPECT_EQ(a.rows[i].err_e, b.rows[i].err_e);
    EXPECT_EQ(a.rows[i].err_traj, b.rows[i].err_traj);
    EXPECT_EQ(a.rows[i].steps, b.rows[i].steps);
    EXPECT_LT(a.rows[i].err_e, 1e-2);
  }
  EXPECT_LT(a.rows[1].err_e, a.rows[0].err_e);  // rtol 1e-6 closer to the reference than 1e-4
  ASSERT_EQ(b.runs_by_rank.size(), 2u);
  EXPECT_EQ(b.runs_by_rank[0] + b.runs_by_rank[1], 5);  // every run counted once
  EXPECT_FALSE(a.cancelled);
}

TEST(StudyWorkPrecision, ASolverFailureFailsItsRungAlone) {
  auto opt = precision_options({1e-3, 1e-6}, {"cvode-dense"}, {"soe-step", "soe"});
  opt.ref_rtol = 1e-4;
  const WorkPrecisionResult r = work_precision(precision_plan("gg3462", {{"solver.max_steps", "100"}}, opt), threads(2));
  ASSERT_EQ(r.rows.size(), 4u);
  int failed = 0;
  for (const auto& row : r.rows) {
    if (row.ok) continue;
    ++failed;
    EXPECT_EQ(row.message.rfind("solver failure: ", 0), 0u) << row.message;
  }
  EXPECT_GT(failed, 0);
}

TEST(StudyWorkPrecision, CancelledKeepsTheRungsThatFinished) {
  const auto plan = precision_plan("default", {}, precision_options({1e-3, 1e-4, 1e-5, 1e-6}, {"cvode-dense"}, {"soe"}));
  std::size_t done = 0;
  Hooks hooks;
  hooks.progress = [&](std::size_t d, std::size_t total) {
    EXPECT_EQ(total, 5u);
    done = d;
  };
  hooks.cancelled = [&] { return done >= 3; };
  const WorkPrecisionResult r = work_precision(plan, threads(1), hooks);
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(r.rows.size(), 2u);  // the reference and two rungs ran
  EXPECT_EQ(done, 3u);
}

TEST(StudyWorkPrecision, BadOptionsAreRefusedBeforeAnythingRuns) {
  auto opt = precision_options({2.0}, {"cvode-dense"}, {});
  EXPECT_THROW(precision_plan("default", {}, opt), InputError);
  opt = precision_options({1e-4}, {"lsoda"}, {});
  EXPECT_THROW(precision_plan("default", {}, opt), InputError);
  opt = precision_options({1e-4}, {"cvode-gmres"}, {"soe-step"});
  const auto plan = precision_plan("default", {}, opt);  // gmres without soe's modes: skipped, with the reason
  EXPECT_TRUE(plan.rungs.empty());
  ASSERT_EQ(plan.skipped.size(), 1u);
  EXPECT_NE(plan.skipped[0].find("preconditioner"), std::string::npos);
}

/// The validation's table as text, but its wall times.
std::vector<std::string> precision_validate_cells(const ValidateResult& res) {
  std::vector<std::string> cells;
  for (const auto& r : res.rows)
    for (const auto& c : validate_columns(res.flow))
      if (c.name != "wall_time_s") cells.push_back(c.kind == ValidateColumn::word ? c.text({res, r}) : std::to_string(c.value({res, r})));
  return cells;
}

TEST(StudyValidate, RowsAcrossRanksEqualRowsOnThreads) {
  ValidateOptions opt;
  opt.models = {"seed"};
  const ValidateResult a = validate_seed(opt, {}, threads(2));
  const ValidateResult b = validate_seed(opt, {}, precision_two_ranks());
  const std::size_t seeds = read_table_6_1().size();
  ASSERT_EQ(a.rows.size(), 2 * seeds);
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_EQ(a.rows[i].set, i < seeds ? SpeedSet::V_Io : SpeedSet::St_B);
    EXPECT_EQ(a.rows[i].run.e, b.rows[i].run.e);
    EXPECT_EQ(a.rows[i].V, b.rows[i].V);
  }
  EXPECT_EQ(precision_validate_cells(a), precision_validate_cells(b));
  ASSERT_EQ(a.agreement.size(), 2u);
  EXPECT_EQ(a.agreement[0].runs, static_cast<int>(seeds));
  for (std::size_t i = seeds; i < a.rows.size(); ++i) {  // the St_B rows at the printed St_B within 1 %
    const double printed = a.seed_of(a.rows[i]).St_B_value;
    if (a.rows[i].warning.empty()) {
      EXPECT_NEAR(a.rows[i].run.St_B_table_6_1, printed, 0.01 * printed);
    }
  }
}

TEST(StudyValidate, BadOptionsAreRefused) {
  ValidateOptions opt;
  opt.tolerance = 0;
  EXPECT_THROW(validate_seed(opt, {}, threads(1)), InputError);
  opt.tolerance = 0.05;
  EXPECT_THROW(validate_seed(opt, {{"lubrication.model", "\"brenner\""}}, threads(1)), InputError);
  opt.models = {"wall"};
  EXPECT_THROW(validate_seed(opt, {}, threads(1)), InputError);
}

}  // namespace
}  // namespace imcol::study
