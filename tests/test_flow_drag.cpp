// SPDX-License-Identifier: BSD-3-Clause
// Flow kernel physics on coarse grids (each test well under a few seconds): Stokes drag and its first-order
// convergence, the impulsively started sphere against Stokes + Basset, the moving-body (GMRES) path against the
// fixed-body (LU) path, two approaching spheres, and the flow-scene reader's errors.
// The production resolutions (Re 20/100 C_D, wake length, 64+ cells/D) run through `imcol flow` and bench/.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <cstdio>
#include <filesystem>
#include <map>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "core/errors.hpp"
#include "flow/flow_scene.hpp"
#include "flow/solver.hpp"
#include "flow_settings.hpp"
#include "run/flow_references.hpp"

using namespace imcol::flow;
using imcol::flow::test_setup::stream_settings;

namespace {

// Proudman & Pearson (J. Fluid Mech. 2, 1957): F/(6πμaU) = 1 + (3/16)Re + (9/160)Re² ln(Re/2), Re = UD/ν
double proudman_pearson(double Re) { return 1 + 3.0 / 16.0 * Re + 9.0 / 160.0 * Re * Re * std::log(Re / 2); }

double steady_stokes_ratio_run(int cpd) {
  const double Re = 0.1;
  // backward Euler with a large step (U²Δt/ν = 0.16) to t = 160, where F has settled to 1e-4
  Solver s(stream_settings(Re, cpd, 8, 1.5, -1.5, 1.5, 1.6, 1.0), {{0.5, 0.0, 0.0}});
  double F = 0;
  for (int n = 0; n < 100; ++n) F = s.step({{0.5, 0.0, 0.0}}).force[0];
  return F / (6 * M_PI * (1.0 / Re) * 0.5);
}

// F/(6πμaU) at the steady state, Re = 0.1, 8 levels of r < 1.5, |z| < 1.5 (computed once per resolution)
double steady_stokes_ratio(int cpd) {
  static std::map<int, double> cache;
  auto it = cache.find(cpd);
  if (it == cache.end()) it = cache.emplace(cpd, steady_stokes_ratio_run(cpd)).first;
  return it->second;
}

}  // namespace

TEST(FlowDrag, StokesDragConvergesToProudmanPearsonAtFirstOrder) {
  const double pp = proudman_pearson(0.1);
  const double f16 = steady_stokes_ratio(16), f32 = steady_stokes_ratio(32);
  const double e16 = f16 / pp - 1, e32 = f32 / pp - 1;
  const double order = std::log2(e16 / e32);
  const double extrap = 2 * f32 - f16;  // Richardson, first order
  std::printf("F/(6 pi mu a U): 16 cells/D %.4f, 32 cells/D %.4f, extrapolated %.4f; Proudman-Pearson %.4f\n", f16, f32, extrap, pp);
  std::printf("error vs Proudman-Pearson: %.2f %%, %.2f %% (observed order %.2f); extrapolated %.2f %%\n", 100 * e16, 100 * e32,
              order, 100 * (extrap / pp - 1));
  EXPECT_LT(std::abs(e32), 0.03);                // 32 cells/D, 8 levels: within 3 %
  EXPECT_GT(order, 0.8);                         // immersed boundary: first order
  EXPECT_LT(std::abs(extrap / pp - 1), 0.01);    // extrapolated: within 1 %
  EXPECT_LT(std::abs(extrap - 1), 0.03);         // and within 3 % of 6πμaU
}

TEST(FlowDrag, NestedLevelsReproduceOneLargeLevel) {
  // Steady Stokes drag (Re = 0.1, 16 cells/D) with 4 nested levels of 24 × 48 cells against one level of
  // 192 × 384 cells covering the same outer domain (r < 12 D, |z| < 12 D): the far field through the levels.
  auto drag = [](int levels, int nr, int nz) {
    Settings st = stream_settings(0.1, 16, levels, nr / 16.0, -nz / 32.0, nz / 32.0, 1.6, 1.0);
    Solver s(st, {{0.5, 0.0, 0.0}});
    double F = 0;
    for (int n = 0; n < 100; ++n) F = s.step({{0.5, 0.0, 0.0}}).force[0];
    return F;
  };
  const double nested = drag(4, 24, 48), single = drag(1, 192, 384);
  std::printf("F nested (4 levels) %.5f, single level %.5f, difference %.3f %%\n", nested, single, 100 * (nested / single - 1));
  EXPECT_NEAR(nested / single, 1.0, 0.005);
}

TEST(FlowDrag, ImpulsivelyStartedSphereFollowsStokesPlusBasset) {
  // F(t) = 6πμaU (1 + a/√(πνt)) for t > 0 at Re → 0; Re = 0.1, Crank–Nicolson, Δt = 0.001, 0.02 ≤ t ≤ 0.1
  // (νt/a² = 0.8 … 4). Raw: against that formula. Bias-corrected: the grid's steady first-order bias b = S/S_PP
  // (S = steady F/6πμaU on the same grid, S_PP Proudman–Pearson at Re = 0.1; the Oseen part of S_PP develops only
  // for t ~ ν/U² = 10) read as an effective radius a' = a b: F(t) against 6πμa'U (1 + a'/√(πνt)).
  // Early steps: see NestedLevelsAddNoRingingAfterAbruptStarts.
  double err[2] = {0, 0}, cerr[2] = {0, 0};
  int c = 0;
  for (int cpd : {16, 32}) {
    const double dt = 0.001, nu = 10.0, a = 0.5;
    const double steady = steady_stokes_ratio(cpd), bias = steady / proudman_pearson(0.1), a_eff = a * bias;
    Solver s(stream_settings(0.1, cpd, 8, 1.5, -1.5, 1.5, dt, 0.5), {{a, 0.0, 0.0}});
    for (int n = 1; n <= 100; ++n) {
      const double F = s.step({{a, 0.0, 0.0}}).force[0];
      const double t = n * dt, basset = 1 + a / std::sqrt(M_PI * nu * t), fs = 6 * M_PI * nu * a;
      if (t >= 0.02 - 1e-12) {
        err[c] = std::max(err[c], std::abs(F / (fs * basset) - 1));
        cerr[c] = std::max(cerr[c], std::abs(F / (fs * bias * (1 + a_eff / std::sqrt(M_PI * nu * t))) - 1));
      }
    }
    std::printf("%d cells/D, 0.02 <= t <= 0.1: max |F/F_ref - 1| %.2f %%; bias-corrected (steady F/6 pi mu a U = %.4f, a'/a = %.4f) %.2f %%\n",
                cpd, 100 * err[c], steady, a_eff / a, 100 * cerr[c]);
    ++c;
  }
  EXPECT_LT(err[0], 0.08);
  EXPECT_LT(err[1], 0.05);
  EXPECT_LT(err[1], 0.65 * err[0]);  // converges with the grid
  // once the grid's steady bias is removed the unsteady force is right to ~1 % at both resolutions (0.6 %, 0.9 %:
  // what is left does not fall with h; it is largest at the window's start, so it is the time step's, not the grid's)
  EXPECT_LT(cerr[0], 0.015);
  EXPECT_LT(cerr[1], 0.015);
}

TEST(FlowDrag, ImpulsiveStartImpulseIsAddedMassPlusInternalFluid) {
  // Re = 1000, first 10 steps of a stream switched on around a fixed sphere. The ring forces stop the fluid inside
  // and push the fluid around it: their impulse is the potential-flow 1.5ρVU (ρV for the fluid inside, ½ρV added
  // mass) plus a small Stokes + Basset part 6πμaU (T + 2a√(T/(πν))). The hydrodynamic impulse (ring forces + the
  // fluid inside going from U to 0 on step 1, solver.hpp) is ½ρVU + viscous. Both converge at first order with h:
  // the regularised delta thickens the body, which raises its volume-like terms most (the added-mass estimate
  // carries three times the relative volume error of the ring impulse).
  double ring[2], hydro[2];
  int c = 0;
  for (int cpd : {16, 32}) {
    const double dt = 0.001, nu = 1e-3, T = 0.01, a = 0.5;
    Solver s(stream_settings(1.0 / nu, cpd, 3, 1.5, -1.5, 1.5, dt, 0.5), {{a, 0.0, 0.0}});
    double impulse = 0, internal = 0;
    for (int n = 0; n < 10; ++n) {
      const StepInfo info = s.step({{a, 0.0, 0.0}});
      impulse += info.force[0] * dt;
      internal += info.internal[0] * dt;
    }
    const double viscous = 6 * M_PI * nu * a * (T + 2 * a * std::sqrt(T / (M_PI * nu)));
    const double V = 4.0 / 3.0 * M_PI * a * a * a;
    ring[c] = (impulse - internal - viscous) / (1.5 * V);
    hydro[c] = (impulse - viscous) / (0.5 * V);
    std::printf("%d cells/D: impulse %.4f (fluid inside %.4f), viscous part %.4f; ring impulse/(1.5 rho V U) = %.4f, "
                "(impulse - viscous)/(0.5 rho V U) = %.4f\n", cpd, impulse, internal, viscous, ring[c], hydro[c]);
    ++c;
  }
  EXPECT_LT(std::abs(ring[1] - 1), 0.2);
  EXPECT_LT(std::abs(ring[1] - 1), 0.6 * std::abs(ring[0] - 1));
  EXPECT_LT(std::abs(hydro[1] - 1), 0.6 * std::abs(hydro[0] - 1));  // 2.0 -> 1.44: first order towards ½ρVU
}

TEST(FlowDrag, NestedLevelsAddNoRingingAfterAbruptStarts) {
  // The first 10 steps after an abrupt start, 3 nested levels of 24 × 48 cells against one level of 96 × 192 over
  // the same outer domain (16 cells/D): the body force must reach the coarse levels in the same step (no lag).
  // (a) Re = 1000, stream switched on around a fixed sphere (LU path); (b) Re = 10, a sphere set moving at −U
  // through fluid at rest, crossing grid lines (GMRES path). Measured: 3e-5 and 2.5e-5; the lagged coupling
  // replaced in this revision gave 970 and 1.26 here (steps 1-4 at Re 1000: 1109.8, -93.8, 55.0, -8.5 against
  // 1064.8, 0.097, 0.098, 0.098).
  auto run = [](bool moving, int levels, int nr, int nz) {
    Settings st = stream_settings(moving ? 10 : 1000, 16, levels, nr / 16.0, -nz / 32.0, nz / 32.0, moving ? 0.01 : 0.001, 0.5);
    if (moving) st.u_inf = 0;
    st.krylov_tol = 1e-12;
    const double z0 = moving ? 0.2 : 0.0, u = moving ? -1.0 : 0.0;
    Solver s(st, {{0.5, z0, u}});
    std::vector<double> F;
    for (int n = 1; n <= 10; ++n) F.push_back(s.step({{0.5, z0 + u * n * st.dt, u}}).force[0]);
    return F;
  };
  for (bool moving : {false, true}) {
    const auto nested = run(moving, 3, 24, 48), single = run(moving, 1, 96, 192);
    double worst = 0;
    for (int n = 0; n < 10; ++n) {
      const double rel = std::abs(nested[n] / single[n] - 1);
      worst = std::max(worst, rel);
      if (n < 3 || n == 9)
        std::printf("%s step %d: nested %.6f, single %.6f\n", moving ? "moving Re 10" : "impulsive Re 1000", n + 1, nested[n], single[n]);
    }
    std::printf("%s: max relative difference over steps 1-10 %.2e\n", moving ? "moving Re 10" : "impulsive Re 1000", worst);
    EXPECT_LT(worst, 1e-3);
  }
}

TEST(FlowDrag, OscillatingSphereFollowsUnsteadyStokes) {
  // z = A(1 − cos ωt), ν = 1, a = 0.5, ω = 32 (δ = √(2ν/ω) = a/2), A = 0.01: the periodic unsteady Stokes force
  // F = −6πμa(1 + a/δ)U − 3πa²√(2μρ/ω)(1 + 2a/(9δ)) dU/dt (Landau & Lifshitz §24), compared over the second
  // period at mid-step (the step's force is its average). Moving body: GMRES, internal fluid included.
  const double a = 0.5, nu = 1.0, om = 32.0, A = 0.01, T = 2 * M_PI / om, delta = std::sqrt(2 * nu / om);
  const int per = 100;
  const double dt = T / per;
  auto ref = [&](double t) {
    const double U = A * om * std::sin(om * t), dU = A * om * om * std::cos(om * t);
    return -6 * M_PI * nu * a * (1 + a / delta) * U - 3 * M_PI * a * a * std::sqrt(2 * nu / om) * (1 + 2 * a / (9 * delta)) * dU;
  };
  double err[2];
  int c = 0;
  for (int cpd : {12, 24}) {
    Settings st = stream_settings(1.0, cpd, 4, 1.5, -1.5, 1.5, dt, 0.5);
    st.u_inf = 0;
    st.krylov_tol = 1e-8;  // the force to ~1e-8: far below the % errors checked here
    Solver s(st, {{a, 0.0, 0.0}});
    double e = 0, amp = 0;
    for (int n = 1; n <= 2 * per; ++n) {
      const double t = n * dt;
      const double F = s.step({{a, A * (1 - std::cos(om * t)), A * om * std::sin(om * t)}}).force[0];
      if (n > per) {
        e = std::max(e, std::abs(F - ref(t - 0.5 * dt)));
        amp = std::max(amp, std::abs(ref(t - 0.5 * dt)));
      }
    }
    err[c] = e / amp;
    std::printf("%d cells/D: max |F - F_Stokes| over the 2nd period = %.2f %% of the amplitude\n", cpd, 100 * err[c]);
    ++c;
  }
  EXPECT_LT(err[1], 0.15);
  EXPECT_LT(err[1], 0.6 * err[0]);
}

TEST(FlowDrag, KrylovPathMatchesDirectPath) {
  auto run = [](bool direct) {
    Settings st = stream_settings(20, 16, 2, 1.5, -1.5, 1.5, 0.01, 0.5);
    st.direct_when_fixed = direct;
    st.krylov_tol = 1e-12;
    Solver s(st, {{0.5, 0.0, 0.0}});
    StepInfo info;
    for (int n = 0; n < 20; ++n) info = s.step({{0.5, 0.0, 0.0}});
    return std::make_pair(info.force[0], info.krylov_iterations);
  };
  const auto [fd, itd] = run(true);
  const auto [fc, itc] = run(false);
  std::printf("after 20 steps: LU %.12f, GMRES %.12f (%d iterations on the last step)\n", fd, fc, itc);
  EXPECT_EQ(itd, 0);
  EXPECT_GT(itc, 0);
  EXPECT_NEAR(fc, fd, 1e-8 * std::abs(fd));
}

TEST(FlowDrag, KrylovSolveMeetsItsToleranceOnTheTrueResidual) {
  // Two fixed spheres in a stream (two preconditioner blocks, so GMRES iterates) and a restart of 3 (so
  // it restarts): the force matches LU, the no-slip residual after the step follows krylov_tol, a looser
  // tolerance takes fewer iterations, and an iteration limit ends with a SolverError naming the residual.
  const std::vector<SphereState> spheres = {{0.5, -0.75, 0.0}, {0.5, 0.75, 0.0}};
  auto run = [&](bool direct, double tol, int restart, int steps) {
    Settings st = stream_settings(20, 16, 2, 1.5, -2.0, 2.0, 0.01, 0.5);
    st.direct_when_fixed = direct;
    st.krylov_tol = tol;
    st.krylov_restart = restart;
    Solver s(st, spheres);
    StepInfo info;
    int iters = 0;
    for (int n = 0; n < steps; ++n) {
      info = s.step(spheres);
      iters += info.krylov_iterations;
    }
    return std::make_pair(info, iters);
  };
  const auto [lu, lu_it] = run(true, 1e-12, 60, 5);
  const auto [tight, tight_it] = run(false, 1e-12, 3, 5);
  const auto [loose, loose_it] = run(false, 1e-4, 3, 5);
  std::printf("LU slip %.2e; GMRES(3) tol 1e-12: %d iterations, residual %.2e, slip %.2e; tol 1e-4: %d iterations, slip %.2e\n",
              lu.slip, tight_it, tight.krylov_residual, tight.slip, loose_it, loose.slip);
  EXPECT_EQ(lu_it, 0);
  EXPECT_LT(lu.slip, 1e-12);
  EXPECT_GT(tight_it, 5 * 3);  // restarted at least once per step on average
  EXPECT_LE(tight.krylov_residual, 1e-12);
  EXPECT_LT(tight.slip, 1e-9);
  EXPECT_NEAR(tight.force[0], lu.force[0], 1e-8 * std::abs(lu.force[0]));
  EXPECT_NEAR(tight.force[1], lu.force[1], 1e-8 * std::abs(lu.force[1]));
  EXPECT_LT(loose_it, tight_it);
  EXPECT_GT(loose.slip, tight.slip);
  try {
    Settings st = stream_settings(20, 16, 2, 1.5, -2.0, 2.0, 0.01, 0.5);
    st.direct_when_fixed = false;
    st.krylov_tol = 1e-14;
    st.krylov_max_iter = 2;
    Solver s(st, spheres);
    s.step(spheres);
    FAIL() << "expected a SolverError";
  } catch (const imcol::SolverError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("did not converge in 2 iterations"), std::string::npos) << msg;
    EXPECT_NE(msg.find("true relative residual"), std::string::npos) << msg;
    EXPECT_NE(msg.find("e-"), std::string::npos) << msg;  // numbers in scientific notation, not 0.000000
    // The keys named are the [flow] table's (collision and flow scenes alike), not [solver]'s.
    EXPECT_NE(msg.find("flow.krylov_max_iter"), std::string::npos) << msg;
    EXPECT_NE(msg.find("flow.krylov_tol"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("solver."), std::string::npos) << msg;
  }
}

TEST(FlowDrag, MovingSphereInQuiescentFluidMatchesFixedSphereInStream) {
  // Galilean invariance for t > 0: a sphere set moving at −U in fluid at rest feels the force of a fixed
  // sphere in an impulsively started stream U. Re = 10, 16 cells/D; the moving sphere crosses half a diameter.
  const double dt = 0.01;
  Settings fixed = stream_settings(10, 16, 3, 1.5, -2.0, 2.0, dt, 0.5);
  Settings moving = fixed;
  moving.u_inf = 0;
  moving.krylov_tol = 1e-10;
  Solver a(fixed, {{0.5, 0.0, 0.0}});
  Solver b(moving, {{0.5, 0.25, -1.0}});
  double worst = 0;
  int iters = 0;
  for (int n = 1; n <= 50; ++n) {
    const StepInfo ia = a.step({{0.5, 0.0, 0.0}});
    const double Fa = ia.force[0];
    const StepInfo ib = b.step({{0.5, 0.25 - n * dt, -1.0}});
    iters = std::max(iters, ib.krylov_iterations);
    if (n == 1) {  // step 1: the fluid inside goes from U∞ = 1 to 0 (fixed) and from 0 to −1 (moving), the same change
      EXPECT_NEAR(ib.internal[0], -4.0 / 3.0 * M_PI * 0.125 / dt, 1e-9);
      EXPECT_NEAR(ib.internal[0], ia.internal[0], 1e-9);
      std::printf("step 1: moving %.4f, fixed %.4f (fluid inside %.4f)\n", ib.force[0], Fa, ib.internal[0]);
    } else {
      EXPECT_EQ(ib.internal[0], 0.0);
    }
    if (n >= 10) worst = std::max(worst, std::abs(ib.force[0] / Fa - 1));  // both along +z (drag on a sphere moving to −z)
  }
  std::printf("max relative difference for 0.1 <= t <= 0.5: %.2f %% (GMRES at most %d iterations)\n", 100 * worst, iters);
  EXPECT_LT(worst, 0.02);
  EXPECT_GT(iters, 0);
}

TEST(FlowDrag, TwoSpheresApproachingSymmetricallyFeelEqualAndOppositeForces) {
  const double dt = 0.01;
  Settings st = stream_settings(10, 16, 3, 1.5, -2.0, 2.0, dt, 0.5);
  st.u_inf = 0;
  st.krylov_tol = 1e-10;
  Solver two(st, {{0.5, -1.0, 0.5}, {0.5, 1.0, -0.5}});
  Solver one(st, {{0.5, -1.0, 0.5}});
  StepInfo i2, i1;
  for (int n = 1; n <= 50; ++n) {  // gap from 1 D to 0.5 D
    i2 = two.step({{0.5, -1.0 + 0.5 * n * dt, 0.5}, {0.5, 1.0 - 0.5 * n * dt, -0.5}});
    i1 = one.step({{0.5, -1.0 + 0.5 * n * dt, 0.5}});
  }
  std::printf("gap 0.5 D: F1 = %.6f, F2 = %.6f; single sphere %.6f (GMRES %d iterations)\n", i2.force[0], i2.force[1], i1.force[0],
              i2.krylov_iterations);
  EXPECT_NEAR(i2.force[0], -i2.force[1], 1e-6 * std::abs(i2.force[0]));
  EXPECT_LT(i2.force[0], 0.0);                           // resisted
  EXPECT_LT(i2.force[0], i1.force[0]);                   // more than alone (the squeezed gap)
}

TEST(FlowScene, ReaderRejectsBadInputNamingFileLineAndKey) {
  namespace fs = std::filesystem;
  const std::string good = R"([fluid]
density = 1.0
viscosity = 0.01
[stream]
velocity = 1.0
[[sphere]]
diameter = 1.0
position = 0.0
[grid]
cells_per_diameter = 16
levels = 2
[time]
dt = 0.01
t_end = 1.0
[flow]
krylov_tol = 1e-8
)";
  const fs::path p = fs::temp_directory_path() / "imcol_flow_scene_test.toml";
  auto expect_error = [&](const std::string& text, const std::string& key, const std::string& line) {
    std::ofstream(p) << text;
    try {
      load_flow_scene(p.string());
      ADD_FAILURE() << "accepted a bad scene (" << key << ")";
    } catch (const imcol::InputError& e) {
      EXPECT_EQ(e.key(), key) << e.what();
      EXPECT_NE(e.where().find(p.string() + line), std::string::npos) << e.what();
    }
  };
  std::ofstream(p) << good;
  const FlowScene sc = load_flow_scene(p.string());
  EXPECT_DOUBLE_EQ(sc.Re(), 100.0);
  auto replace = [&](std::string from, std::string to) {
    std::string t = good;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  expect_error(replace("viscosity = 0.01", "viscosity = -0.01"), "fluid.viscosity", ":3");
  expect_error(replace("levels = 2", "levels = 2\nlevles = 3"), "grid.levles", ":12");
  expect_error(replace("krylov_tol = 1e-8", "krylov_tol = 0"), "flow.krylov_tol", ":16");
  expect_error(replace("[flow]", "[solver]"), "solver", ":15");  // [solver] is the ODE solver of collision scenes
  expect_error(replace("position = 0.0", "position = 9.0"), "sphere[0]", ":6");       // outside the finest level
  expect_error(replace("t_end = 1.0", "t_end = 0.001"), "time.dt", ":13");          // dt > t_end
  expect_error(replace("velocity = 1.0", "velocity = 0.0"), "stream.velocity", ":5");  // no relative motion
  expect_error(good + "[[sphere]]\ndiameter = 1.0\nposition = 0.5\n", "sphere[1]", ":17");  // the second sphere overlaps
  expect_error(good + "[[sphere]]\ndiameter = 1.0\nposition = 1.5\nvelocity = -1.0\n", "sphere[1]", ":17");  // by t_end
  // problems caused by command-line overrides are blamed on the command line
  {
    std::ofstream(p) << good;
    FlowScene sc2 = load_flow_scene(p.string());
    sc2.t_end = 0.001;
    sc2.overridden.insert("--t-end");
    try {
      check_flow_scene(sc2);
      ADD_FAILURE() << "accepted dt > t_end";
    } catch (const imcol::InputError& e) {
      EXPECT_EQ(e.where(), "command line (--t-end)") << e.what();
    }
    sc2 = load_flow_scene(p.string());
    sc2.cells_per_diameter = 4;  // grid of 2 D: the sphere no longer sits 3 cells inside it
    sc2.r_max = 1.0;
    sc2.overridden.insert("--cells");
    try {
      check_flow_scene(sc2);
      ADD_FAILURE() << "accepted a sphere outside the finest level";
    } catch (const imcol::InputError& e) {
      EXPECT_EQ(e.where(), "command line (--cells)") << e.what();
    }
  }
  fs::remove(p);
}

TEST(FlowCommand, WritesSummaryAndForcesAndRejectsBadScenes) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("imcol_flow_cli_" + std::to_string(::getpid()));
  const fs::path scene = dir.string() + ".toml";
  std::ofstream(scene) << R"(name = "tiny"
[fluid]
density = 1.0
viscosity = 0.05
[stream]
velocity = 1.0
[[sphere]]
diameter = 1.0
[grid]
cells_per_diameter = 8
levels = 2
r_max = 1.5
z_min = -1.5
z_max = 1.5
[time]
dt = 0.05
t_end = 0.5
)";
  const std::string cmd = std::string(IMCOL_BINARY) + " flow " + scene.string() + " --no-plot --out " + dir.string() + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(dir / "summary.json");
  const auto j = nlohmann::json::parse(in);
  for (const char* k : {"drag_coefficient", "Re", "grid", "steps", "wall_time_s"}) EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["steps"].get<int>(), 10);
  EXPECT_DOUBLE_EQ(j["Re"].get<double>(), 20.0);
  EXPECT_GT(j["drag_coefficient"].get<double>(), 0.0);
  EXPECT_TRUE(fs::exists(dir / "forces.csv"));
  EXPECT_TRUE(fs::exists(dir / "snapshot_00.csv"));
  std::ofstream(scene, std::ios::app) << "theta = 2.0\n";  // out of range
  const int raw = std::system((std::string(IMCOL_BINARY) + " flow " + scene.string() + " --no-plot >/dev/null 2>&1").c_str());
  EXPECT_EQ(WEXITSTATUS(raw), 2);
  fs::remove_all(dir);
  fs::remove(scene);
}

// f_THR's collision scene, built in code, is the scene this TOML text gives: the same forces to the last bit.
TEST(FlowReferences, PairSceneBuiltInCodeIsItsToml) {
  FlowScene fs;
  fs.path = "two.toml";
  fs.density = 1000;
  fs.viscosity = 0.01;
  fs.spheres = {{0.002, -0.004, 0.3}, {0.003, 0.0, -0.1}};
  std::ostringstream t;
  t << std::setprecision(17) << "effects = [\"drag\", \"lubrication\", \"added_mass\", \"elastic\"]\n[fluid]\ndensity = " << fs.density
    << "\nviscosity = " << fs.viscosity << "\n";
  for (const auto& b : fs.spheres)
    t << "[[sphere]]\ndensity = " << 2 * fs.density << "\nyoungs_modulus = 1e9\npoisson_ratio = 0.3\ne_dry = 1.0\ndiameter = " << b.diameter
      << "\nposition = " << b.position << "\nvelocity = " << b.velocity << "\n";
  t << "[drag]\nlaw = \"schiller-naumann\"\n";
  const imcol::model::CollisionModel parsed(imcol::parse_scene(t.str(), "two.toml"));
  const imcol::AnalyticPairForce built(fs);
  for (double gap : {2e-3, 5e-4, 1e-4, 3e-5, 1e-6}) {
    const std::vector<SphereState> s = {{0.001, -gap - 0.0025, 0.3}, {0.0015, 0.0, -0.1}};
    const double h = s[1].z - s[0].z - s[0].radius - s[1].radius;  // the surface gap, as the states give it
    const std::array<double, 4> y = {h, s[0].u, s[1].z, s[1].u};
    const auto f = parsed.analytic_fluid_force(0.0, y, {0.0, 0.0});
    const auto [f1, f2] = built.at(s);
    EXPECT_EQ(f1, f[0]) << "gap " << gap;
    EXPECT_EQ(f2, f[1]) << "gap " << gap;
    EXPECT_NE(f1, 0.0);
  }
}
