// SPDX-License-Identifier: BSD-3-Clause
// The adaptive flow step (coupling/adaptive_step.hpp) and what the kernel does when its step changes
// (flow/solver.hpp set_dt, flow/grid.hpp FastSolver::set_op).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/scene.hpp"
#include "coupling/adaptive_step.hpp"
#include "coupling/reference_speed.hpp"
#include "coupling/step_rule.hpp"
#include "flow/grid.hpp"
#include "flow/solver.hpp"
#include "run/simulate.hpp"

using namespace imcol;

namespace {

Scene adaptive_scene(const std::vector<Override>& ov = {}) {
  return load_scene(std::string(IMCOL_DATA_DIR) + "/scenes/coupled/gondret_st742.toml", ov);
}

/// The sphere of gondret_st742 at centre z (m) and speed u (m/s), stepped `steps` times; returns the last step.
double adaptive_steps(coupling::AdaptiveStep& a, double z, double u, int steps, double u_fluid = 0) {
  std::array<double, 1> zz{z}, uu{u};
  double dt = 0;
  for (int k = 0; k < steps; ++k) dt = a.next(zz, uu, u_fluid);
  return dt;
}

flow::Settings set_dt_settings() {
  flow::Settings s;  // D = 1, Re = 20 in the stream; finest level r < 1.5 D, −2 D < z < 3 D
  s.nu = 0.05;
  s.dt = 0.02;
  s.h = 1.0 / 8;
  s.nr = 12;
  s.nz = 40;
  s.levels = 2;
  s.z_center = 0.5;
  s.u_inf = 1.0;
  s.krylov_tol = 1e-10;
  s.preconditioner_bins = 4;
  s.direct_when_fixed = false;
  return s;
}

/// The force on a sphere held at z = 0 in the stream after `first` steps of dt and `second` steps of dt2.
double held_sphere_force(int first, double dt, int second, double dt2, long* blocks = nullptr) {
  flow::Settings st = set_dt_settings();
  st.dt = dt;
  flow::Solver s(st, {{0.5, 0.0, 0.0}});
  double f = 0;
  // a sphere that creeps by a hundredth of a cell a step: GMRES with the preconditioner blocks, not the LU
  for (int k = 1; k <= first + second; ++k) {
    if (k == first + 1) s.set_dt(dt2);
    f = s.step({{0.5, 1e-3 * st.h * k, 0.0}}).force[0];
  }
  if (blocks) *blocks = s.preconditioner_blocks_built();
  return f;
}

}  // namespace

TEST(AdaptiveStep, SetOpEqualsAFreshSolverForThatOperator) {
  flow::LevelGeometry g;
  g.nr = 10;
  g.nz = 24;
  g.h = 0.1;
  g.z0 = -1.2;
  flow::FastSolver a(g, {{0.0, 1.0}, {1.0, -0.3}}), b(g, {{0.0, 1.0}, {1.0, -0.05}});
  a.set_op(1, {1.0, -0.05});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<double> f(g.size()), xa(g.size(), 0.0), xb(g.size(), 0.0);
  for (double& v : f) v = U(rng);
  a.solve(1, f, xa);
  b.solve(1, f, xb);
  EXPECT_EQ(xa, xb);
  EXPECT_THROW(a.set_op(2, {1.0, 0.0}), std::out_of_range);
}

TEST(AdaptiveStep, ASlowerSphereGetsALongerStepGrowingByAtMostKGrowByAtATime) {
  const Scene sc = adaptive_scene();
  const double D = sc.spheres[0].diameter, h = D / sc.flow.cells_per_diameter;
  const coupling::FlowStep first = coupling::flow_step(sc, h);
  coupling::AdaptiveStep a(sc, h, first);
  ASSERT_TRUE(a.active());
  const double z0 = sc.spheres[0].position, u0 = sc.spheres[0].velocity;
  // At the initial state the step is the rule's first one.
  EXPECT_EQ(adaptive_steps(a, z0, u0, 30), first.dt);
  EXPECT_EQ(a.changes(), 0);
  // Rebounded at a third of the speed from the wall (no fall left): U = u0/3, the rule's step 3 Δt_0.
  const double z_wall = sc.wall->position - 0.5 * D, u = -u0 / 3;
  std::array<double, 1> toward{u0 / 3};
  EXPECT_FALSE(a.separating(toward));  // moving toward the wall at that speed the step would not grow
  coupling::AdaptiveStep approaching(sc, h, first);
  EXPECT_EQ(adaptive_steps(approaching, z_wall, u0 / 3, 40), first.dt);
  std::array<double, 1> zz{z_wall}, uu{u};
  const double target = a.rule(coupling::reference_speed(sc, zz, uu).u);
  EXPECT_NEAR(target, first.cfl * h / (u0 / 3), 1e-12 * target);
  double dt = first.dt;
  int since = 30;  // the steps already taken at the first step
  for (int k = 0; k < 100; ++k) {
    const double next = a.next(zz, uu, 0.0);
    ++since;
    if (next != dt) {
      EXPECT_LE(next, coupling::kGrowBy * dt * (1 + 1e-12));
      EXPECT_GE(since, coupling::kSteadySteps);
      since = 0;
    }
    dt = next;
  }
  EXPECT_LE(dt, target);
  EXPECT_GT(dt, target / coupling::kGrowFrom);
  // The fluid moving faster than 4 U withholds growth; it never shrinks the step.
  coupling::AdaptiveStep b(sc, h, first);
  EXPECT_EQ(adaptive_steps(b, z_wall, u, 40, 4 * u0), first.dt);
  // Back at the first speed: the step shrinks at once to the rule's.
  const double back = adaptive_steps(a, z0, u0, 1);
  EXPECT_NEAR(back, first.dt, 1e-9 * first.dt);
}

TEST(AdaptiveStep, AGivenStepOrTheKeyOffKeepsTheFirstStep) {
  for (const std::vector<Override>& ov : std::vector<std::vector<Override>>{{{"flow.dt", "1e-4"}}, {{"flow.adaptive_step", "false"}}}) {
    const Scene sc = adaptive_scene(ov);
    const double h = sc.spheres[0].diameter / sc.flow.cells_per_diameter;
    const coupling::FlowStep first = coupling::flow_step(sc, h);
    coupling::AdaptiveStep a(sc, h, first);
    EXPECT_FALSE(a.active());
    EXPECT_EQ(adaptive_steps(a, sc.wall->position - sc.spheres[0].diameter, 0.01, 50), first.dt);
  }
  EXPECT_THROW(adaptive_scene({{"flow.dt", "1e-4"}, {"flow.adaptive_step", "true"}}), InputError);
  EXPECT_NO_THROW(adaptive_scene({{"flow.dt", "1e-4"}, {"flow.adaptive_step", "false"}}));
}

TEST(AdaptiveStep, TheKernelAfterAStepChangeStaysCloserToTheFineRunThanAllCoarseSteps) {
  // Variable-step AB2 and the viscous operator refactorised: 40 steps of Δt, against 20 of Δt then 10 of 2Δt, and
  // against 20 of 2Δt, all to the same time. The changed run must be nearer the fine one than the coarse run is.
  const double dt = 0.02;
  const double fine = held_sphere_force(40, dt, 0, dt);
  long blocks_changed = 0, blocks_fine = 0;
  const double changed = held_sphere_force(20, dt, 10, 2 * dt, &blocks_changed);
  held_sphere_force(40, dt, 0, dt, &blocks_fine);
  const double coarse = held_sphere_force(0, dt, 20, 2 * dt);
  ASSERT_TRUE(std::isfinite(changed));
  EXPECT_LT(std::abs(changed - fine), std::abs(coarse - fine));
  EXPECT_NE(changed, coarse);
  // θνΔΔt/h² = 0.5 · 0.05 · 0.02 · 64 = 0.032 ≤ kBlockViscousChange: the blocks are reused, scaled.
  EXPECT_EQ(blocks_changed, blocks_fine);
  // A change beyond it (0.5 · 0.05 · 0.78 · 64 = 1.25) rebuilds them.
  long blocks_big = 0;
  held_sphere_force(20, dt, 2, 40 * dt, &blocks_big);
  EXPECT_GT(blocks_big, blocks_fine);
}

TEST(AdaptiveStep, BouncesToTheSameFirstEInFewerFlowSteps) {
  // gondret_st742 coarse (12 cells/D) over its first two bounces: the adaptive step leaves the first bounce's e
  // (measured before the step changes) within the force solve's reach of the fixed step's, and takes fewer steps.
  auto run = [](const char* adaptive) {
    return simulate(adaptive_scene({{"flow.fields", "false"}, {"flow.cells_per_diameter", "12"}, {"solver.t_end", "0.25"},
                                    {"flow.adaptive_step", adaptive}}))
        .summary_json;
  };
  const auto a = run("true"), f = run("false");
  EXPECT_NEAR(a["e"].get<double>(), f["e"].get<double>(), 1e-3);
  EXPECT_EQ(a["bounces"].size(), f["bounces"].size());
  EXPECT_LT(1.2 * a["flow"]["steps"].get<double>(), f["flow"]["steps"].get<double>());
  EXPECT_GT(a["flow"]["step_changes"].get<long>(), 0);
  EXPECT_GT(a["flow"]["dt_max_s"].get<double>(), a["flow"]["dt_s"].get<double>());
  EXPECT_EQ(f["flow"]["step_changes"].get<long>(), 0);
  EXPECT_EQ(f["flow"]["dt_max_s"].get<double>(), f["flow"]["dt_s"].get<double>());
  EXPECT_LE(a["flow"]["max_energy_ratio"].get<double>(), 1.0);
}
