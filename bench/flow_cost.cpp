// SPDX-License-Identifier: BSD-3-Clause
// Cost of the immersed-boundary flow kernel: time per step and memory for 1, 2, 3 levels at 32, 64, 128
// cells per diameter (fixed sphere, Re = 100, CFL 0.32), the growth exponent of time with the number of cells,
// and (--steady) the wall time from a cold start to a C_D within 3 % of the standard curve at Re = 100.
// A program that prints timings, not a test.
// (--refine SCENE) runs a flow scene at several resolutions (dt ∝ h) and prints C_D, its error against the standard
// drag curve, the observed order from successive refinements and a first-order Richardson extrapolation.
//   imcol_flow_cost [--cells 32,64,128] [--levels 1,2,3] [--steps 20] [--steady [--steady-cells 48]]
//   imcol_flow_cost --refine data/scenes/flow/fixed_sphere_re20.toml --cells 32,48,64
// (--wall) the plane no-slip wall: the quasi-steady Stokes force on a sphere moving toward the wall at fixed gaps
// against Brenner's λ(h/a), the force on the wall, the same in the sphere's frame (wall and far fluid moving), and the
// cost per step with and without the wall (fixed and moving sphere).
//   imcol_flow_cost --wall --cells 16,32 [--levels 8] [--re 0.1] [--gaps 3,2,1,0.5,0.25,0.125,0.1,0.05] [--steps 100]
// (--alloc) heap allocations per step (malloc, calloc, realloc, aligned: this program counts them all) after warm-up:
// the fixed sphere at Re = 100 (LU) and two spheres approaching (GMRES), 32 cells/D, 4 levels.
//   imcol_flow_cost --alloc
#include <sys/resource.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "contact/formulas.hpp"
#include "core/timing.hpp"
#include "flow/flow_scene.hpp"
#include "flow/solver.hpp"
#include "run/flow_run.hpp"
#include "run/flow_run_json.hpp"

using namespace imcol::flow;
using imcol::seconds_since;
using imcol::WallClock;

// Every heap allocation of this process is counted (glibc's own allocator underneath).
static std::atomic<long> g_allocs{0};
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
void* malloc(std::size_t n) {
  g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t s) {
  g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(n, s);
}
void* realloc(void* p, std::size_t n) {
  g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, n);
}
void* memalign(std::size_t a, std::size_t n) {
  g_allocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_memalign(a, n);
}
void* aligned_alloc(std::size_t a, std::size_t n) { return memalign(a, n); }
int posix_memalign(void** p, std::size_t a, std::size_t n) {
  *p = memalign(a, n);
  return *p ? 0 : ENOMEM;
}
void free(void* p) { __libc_free(p); }
}

namespace {
int alloc_mode() {
  std::printf("heap allocations per step after warm-up (32 cells/D, 4 levels, finest r < 1.5 D)\n");
  std::printf("%34s %8s %10s %12s\n", "case", "warm-up", "steps", "allocs/step");
  for (bool moving : {false, true}) {
    Settings s;
    s.nu = moving ? 0.1 : 0.01;
    s.h = 1.0 / 32;
    s.dt = moving ? 0.005 : 0.0225;
    s.nr = 48;
    s.nz = moving ? 240 : 144;
    s.levels = 4;
    s.z_center = moving ? -2.25 : 0.75;
    s.u_inf = moving ? 0.0 : 1.0;
    s.krylov_tol = 1e-8;
    std::vector<SphereState> sp = moving ? std::vector<SphereState>{{0.5, -4.0, 1.0}, {0.5, 0.0, 0.0}}
                                         : std::vector<SphereState>{{0.5, 0.0, 0.0}};
    Solver solver(s, sp);
    auto adv = [&]() {
      if (moving) sp[0].z += sp[0].u * s.dt;
      solver.step(sp);
    };
    const int warm = 40, steps = 20;
    for (int n = 0; n < warm; ++n) adv();
    const long a0 = g_allocs.load();
    for (int n = 0; n < steps; ++n) adv();
    const double per = static_cast<double>(g_allocs.load() - a0) / steps;
    std::printf("%34s %8d %10d %12.1f\n", moving ? "two spheres approaching, GMRES" : "fixed sphere in a stream, LU", warm, steps, per);
  }
  std::printf("(a step returns StepInfo, whose force and internal vectors are 2 of these)\n");
  return 0;
}


std::vector<double> parse_dlist(const char* s) {
  std::vector<double> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');) v.push_back(std::atof(x.c_str()));
  return v;
}
std::vector<int> parse_list(const char* s) {
  std::vector<int> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');) v.push_back(std::atoi(x.c_str()));
  return v;
}
long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}
// D = 1, U = 1, ρ = 1, ν = 1/Re; wall at z = 0 (sphere on its +z side), finest level r < 1.5 D, −0.5 D < z < 4.5 D.
// Backward Euler with Δt = 1.6 to the steady state (as the Stokes-drag test).
Settings wall_settings(double Re, int cpd, int levels, bool wall, double dt = 1.6, double theta = 1.0) {
  Settings s;
  s.nu = 1.0 / Re;
  s.dt = dt;
  s.theta = theta;
  s.h = 1.0 / cpd;
  s.nr = static_cast<int>(std::lround(1.5 * cpd));
  s.nr += s.nr % 2;
  s.nz = static_cast<int>(std::lround(5.0 * cpd));
  s.nz += (4 - s.nz % 4) % 4;
  s.levels = levels;
  s.z_center = -0.5 + 0.5 * s.nz * s.h;
  if (wall) s.wall_z = 0.0;
  return s;
}

struct WallRun { double F, F_half, wall_force; double setup_s; };
/// Sphere (a = ½) held at surface gap `gap` with surface velocity u_sphere along +z, the wall's surface at u_wall, the
/// far fluid at u_inf: steps until the steady state; F (N along +z), F after half the steps (settling), wall force.
WallRun wall_run(const Settings& base, double gap, double u_sphere, double u_frame, int steps) {
  Settings s = base;
  s.u_inf = u_frame;
  s.wall_velocity = u_frame;
  const SphereState sp{0.5, 0.5 + gap, u_sphere};
  Solver solver(s, {sp});
  WallRun r{};
  const auto t0 = WallClock::now();
  for (int n = 1; n <= steps; ++n) {
    const auto info = solver.step({sp});
    if (n == 1) r.setup_s = seconds_since(t0);
    if (n == steps / 2) r.F_half = info.force[0];
    r.F = info.force[0];
    r.wall_force = info.wall_force;
  }
  return r;
}

int wall_mode(const std::vector<int>& cells, int levels, double Re, const std::vector<double>& gaps, int steps) {
  std::printf("plane wall z = 0, sphere D = 1 moving toward it at U = 1 held at each gap (quasi-steady), Re = %g, %d levels, "
              "finest r < 1.5 D, -0.5 D < z < 4.5 D; backward Euler dt = 1.6, %d steps\n", Re, levels, steps);
  const double mu = 1.0 / Re, a = 0.5, Fst = 6 * M_PI * mu * a;
  for (int c : cells) {
    // the same grid's free sphere (no wall; the same frozen-position set-up) for its bias
    const WallRun free = wall_run(wall_settings(Re, c, levels, false), 3.0, -1.0, 0.0, steps);
    const double S = free.F / Fst;
    std::printf("\n%d cells/D: free sphere (no wall) F/6 pi mu a U = %.4f (the grid's bias), settled to %.1e\n", c, S,
                std::abs(free.F / free.F_half - 1));
    std::printf("%7s %6s %7s %9s %9s %9s %9s %11s %9s %9s %9s\n", "gap/D", "h/a", "cells", "Brenner", "computed", "error%",
                "/free", "err/free%", "-Fwall/F", "frame F", "settle");
    for (double gap : gaps) {
      const double ha = 2 * gap, lam = imcol::contact::brenner_lambda(ha);
      const WallRun w = wall_run(wall_settings(Re, c, levels, true), gap, -1.0, 0.0, steps);
      // the sphere's frame: sphere at rest, the wall and the far fluid moving at +U toward it
      const WallRun f = wall_run(wall_settings(Re, c, levels, true), gap, 0.0, 1.0, steps);
      const double lsim = w.F / Fst;
      std::printf("%7.3f %6.3f %7.2f %9.4f %9.4f %9.2f %9.4f %11.2f %9.4f %9.4f %9.1e%s\n", gap, ha, gap * c, lam, lsim,
                  100 * (lsim / lam - 1), lsim / S, 100 * (lsim / S / lam - 1), -w.wall_force / w.F, f.F / Fst,
                  std::abs(w.F / w.F_half - 1), gap * c < 3 ? "  (gap < 3 cells)" : "");
    }
  }
  // cost per step: fixed sphere (LU) and moving sphere (GMRES), with and without the wall, 32 cells/D (or the last)
  const int c = cells.back();
  std::printf("\ncost per step, %d cells/D, %d levels, Crank-Nicolson dt = 0.01, sphere from a 2 D gap (median of 20 steps after 60 warm-up steps, so that the moving sphere's 16 preconditioner blocks are built; setup = step 1)\n",
              c, levels);
  std::printf("%8s %8s %12s %10s %10s %12s %12s\n", "sphere", "wall", "unknowns", "setup s", "ms/step", "gmres it", "solver MB");
  for (bool moving : {false, true})
    for (bool wall : {false, true}) {
      Settings s = wall_settings(Re, c, levels, wall, 0.01, 0.5);
      SphereState sp{0.5, 0.5 + 2.0, -1.0};
      Solver solver(s, {sp});
      auto adv = [&]() { if (moving) sp.z += sp.u * s.dt; return solver.step({sp}); };
      const auto t0 = WallClock::now();
      adv();
      const double setup = seconds_since(t0);
      for (int n = 0; n < 59; ++n) adv();
      std::vector<double> t;
      long it = 0;
      for (int n = 0; n < 20; ++n) {
        const auto t1 = WallClock::now();
        it += adv().krylov_iterations;
        t.push_back(1e3 * seconds_since(t1));
      }
      std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
      std::printf("%8s %8s %12zu %10.2f %10.3f %12.1f %12.2f\n", moving ? "moving" : "fixed", wall ? "yes" : "no",
                  2 * solver.points().size() + solver.wall_unknowns(), setup, t[t.size() / 2], it / 20.0, solver.bytes() / 1048576.0);
    }
  return 0;
}
/// The observed order p from three successive resolutions (any ratios): solves e_k = C h_k^p by bisection on
/// (h0^p − h1^p)/(h1^p − h2^p) = d01/d12 for p in [0.1, 4]; NaN where no p there fits.
double observed_order(double h0, double h1, double h2, double d01, double d12) {
  auto f = [&](double p) { return (std::pow(h0, p) - std::pow(h1, p)) / (std::pow(h1, p) - std::pow(h2, p)) - d01 / d12; };
  double lo = 0.1, hi = 4.0, p = NAN;
  if (d01 / d12 > 0 && f(lo) * f(hi) < 0) {
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      (f(lo) * f(mid) <= 0 ? hi : lo) = mid;
    }
    p = 0.5 * (lo + hi);
  }
  return p;
}

/// (--refine) the flow scene at each resolution (dt ∝ h): C_D, its error, the observed order, the extrapolation.
int refine_mode(const std::string& path, const std::vector<int>& cells) {
  const imcol::flow::FlowScene sc = imcol::flow::load_flow_scene(path);
  std::printf("%s: Re = %g, %d levels, finest r < %g D, %g D < z < %g D; dt = %g x (%d / cells)\n", sc.name.c_str(), sc.Re(),
              sc.levels, sc.r_max, sc.z_min, sc.z_max, sc.dt, sc.cells_per_diameter);
  std::printf("%8s %10s %10s %9s %12s %10s %10s %10s\n", "cells/D", "C_D", "standard", "error %", "wake L/D", "steps", "wall s", "order");
  std::vector<double> cds;
  for (int c : cells) {
    imcol::FlowRunOptions o;
    o.quiet = true;
    o.cells_per_diameter = c;
    o.dt = sc.dt * sc.cells_per_diameter / c;
    const auto j = imcol::flow_summary_json(imcol::run_flow_scene(sc, o));
    const double cd = j["drag_coefficient"].get<double>();
    cds.push_back(cd);
    std::string order = "-";
    if (cds.size() >= 3) {
      const double h0 = 1.0 / cells[cds.size() - 3], h1 = 1.0 / cells[cds.size() - 2], h2 = 1.0 / c;
      const double d01 = cds[cds.size() - 3] - cds[cds.size() - 2], d12 = cds[cds.size() - 2] - cd;
      char b[32];
      std::snprintf(b, sizeof b, "%.2f", observed_order(h0, h1, h2, d01, d12));
      order = b;
    }
    auto num = [&](const char* k) { return j[k].is_number() ? j[k].get<double>() : NAN; };  // null: drag not settled
    std::printf("%8d %10.4f %10.4f %9.2f %12.4f %10ld %10.2f %10s\n", c, cd, num("drag_coefficient_standard"),
                num("drag_error_percent"), num("wake_length_D"), j["steps"].get<long>(),
                j["wall_time_s"].get<double>(), order.c_str());
  }
  if (cds.size() >= 2) {
    const double h1 = 1.0 / cells[cells.size() - 2], h2 = 1.0 / cells.back();
    const double ex = cds.back() + (cds.back() - cds[cds.size() - 2]) * h2 / (h1 - h2);  // first order
    std::printf("first-order Richardson extrapolation from the two finest: C_D = %.4f\n", ex);
  }
  return 0;
}

struct CostRow { int c, l; double n, ms; };

/// The fixed sphere at Re = 100 on one grid: median ms per step after 3 warm-up steps; prints its row.
CostRow cost_row(int c, int l, int steps) {
  Settings s;
  s.nu = 0.01;
  s.h = 1.0 / c;
  s.dt = 0.32 * s.h;
  s.nr = 2 * c;
  s.nz = 6 * c;
  s.levels = l;
  s.z_center = 1.0;
  s.u_inf = 1.0;
  s.measure_plans = true;
  Solver solver(s, {{0.5, 0.0, 0.0}});
  for (int n = 0; n < 3; ++n) solver.step({{0.5, 0.0, 0.0}});
  std::vector<double> t;
  for (int n = 0; n < steps; ++n) {
    const auto t0 = WallClock::now();
    solver.step({{0.5, 0.0, 0.0}});
    t.push_back(1e3 * seconds_since(t0));
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  const double ms = t[t.size() / 2];
  const double nv = static_cast<double>(l) * (s.nr + 1) * (s.nz + 1);
  char grid[32];
  std::snprintf(grid, sizeof grid, "%dx%d", s.nr, s.nz);
  std::printf("%6d %7d %10s %12.0f %12.3f %12.2f %14.2f\n", c, l, grid, nv, ms, 1e6 * ms / nv, solver.bytes() / 1048576.0);
  return {c, l, nv, ms};
}

/// Time per step and memory for every level count and resolution, and the growth of time with the vertices.
void cost_mode(const std::vector<int>& cells, const std::vector<int>& levels, int steps) {
  std::printf("fixed sphere, Re = 100, finest level r < 2D, -2D < z < 4D, dt = 0.32 h/U; median of %d steps after 3 warm-up steps\n", steps);
  std::printf("%6s %7s %10s %12s %12s %12s %14s\n", "cells/D", "levels", "grid", "vertices", "ms/step", "ns/vertex", "solver MB");
  std::vector<CostRow> rows;
  for (int l : levels)
    for (int c : cells) rows.push_back(cost_row(c, l, steps));
  std::printf("peak resident set of this process: %.1f MB\n", peak_rss_kb() / 1024.0);
  // growth: least-squares slope of log(ms) against log(vertices), per level count
  for (int l : levels) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (const auto& r : rows)
      if (r.l == l) {
        const double x = std::log(r.n), y = std::log(r.ms);
        sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
      }
    if (n >= 2) std::printf("%d level(s): time per step ~ vertices^%.2f\n", l, (n * sxy - sx * sy) / (n * sxx - sx * sx));
  }
}

/// (--steady) the Re = 100 scene from a cold start: when its C_D comes within 3 % of the standard curve.
void steady_mode(int steady_cells) {
  imcol::FlowRunOptions o;
  o.quiet = true;
  if (steady_cells > 0) o.cells_per_diameter = steady_cells;
  const auto j = imcol::flow_summary_json(
      imcol::run_flow_scene(imcol::flow::load_flow_scene(std::string(IMCOL_DATA_DIR) + "/scenes/flow/fixed_sphere_re100.toml"), o));
  std::printf("Re = 100 cold start, %d cells/D, %d levels: C_D = %.4f (standard %.4f, %+.2f %%); within 3 %% from t = %s after %s s wall; "
              "whole run %.2f s for %ld steps\n",
              j["grid"]["cells_per_diameter"].get<int>(), j["grid"]["levels"].get<int>(), j["drag_coefficient"].get<double>(),
              j["drag_coefficient_standard"].is_number() ? j["drag_coefficient_standard"].get<double>() : NAN,
              j["drag_error_percent"].is_number() ? j["drag_error_percent"].get<double>() : NAN, j["time_to_3pct_s"].dump().c_str(),
              j["wall_time_to_3pct_s"].dump().c_str(), j["wall_time_s"].get<double>(), j["steps"].get<long>());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> cells = {32, 64, 128}, levels = {1, 2, 3};
  int steps = 20, steady_cells = 0;
  bool steady = false, wall = false;
  std::string refine;
  int wall_levels = 8, wall_steps = 100;
  double wall_re = 0.1;
  std::vector<double> gaps = {3, 2, 1, 0.5, 0.25, 0.125, 0.1, 0.05};
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--cells" && k + 1 < argc) cells = parse_list(argv[++k]);
    else if (a == "--levels" && k + 1 < argc) levels = parse_list(argv[++k]);
    else if (a == "--steps" && k + 1 < argc) steps = std::atoi(argv[++k]);
    else if (a == "--steady") steady = true;
    else if (a == "--refine" && k + 1 < argc) refine = argv[++k];
    else if (a == "--steady-cells" && k + 1 < argc) steady_cells = std::atoi(argv[++k]);
    else if (a == "--wall") wall = true;
    else if (a == "--alloc") return alloc_mode();
    else if (a == "--re" && k + 1 < argc) wall_re = std::atof(argv[++k]);
    else if (a == "--gaps" && k + 1 < argc) gaps = parse_dlist(argv[++k]);
    else if (a == "--wall-levels" && k + 1 < argc) wall_levels = std::atoi(argv[++k]);
    else if (a == "--wall-steps" && k + 1 < argc) wall_steps = std::atoi(argv[++k]);
    else {
      std::fprintf(stderr, "usage: %s [--cells 32,64,128] [--levels 1,2,3] [--steps N] [--steady [--steady-cells C]]\n", argv[0]);
      return 2;
    }
  }
  if (wall) return wall_mode(cells, wall_levels, wall_re, gaps, wall_steps);
  if (!refine.empty()) return refine_mode(refine, cells);
  cost_mode(cells, levels, steps);
  if (steady) steady_mode(steady_cells);
  return 0;
}
