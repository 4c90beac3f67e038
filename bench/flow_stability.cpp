// SPDX-License-Identifier: BSD-3-Clause
// Where the flow kernel's step breaks: a sphere (D = 1, U = 1, ρ = 1, ν = 1/Re) on a prescribed path, as the coupled
// runs' start-up and approach move it, stepped at Δt = cfl·h/U for a table of Re, cfl and cells per diameter.
//   wall: lab frame, a plane wall at z = 0, the sphere from a gap of 4 D toward it at U until the gap is 0.5 D;
//   pair: the frame of the midpoint, which moves at U/2 (sphere 1 at U toward a target at rest in the lab): stream
//         −U/2, sphere 1 at +U/2, sphere 2 at −U/2, from a gap of 3.5 D to 0.5 D;
//   free: the sphere held in a stream −U (a free sphere's frame), 3 D of travel.
// Outcome per run: "ok", or "diverged" (a force beyond 10× the standard-curve drag ½ρU²πa²·C_D(Re) + 10 ρV U²/D,
// a non-finite force, or GMRES failing), with the step where it happened, the largest advective Courant number of the
// fluid on the finest level (max (|u_r| + |u_z|)Δt/h, lab velocities relative to the grid) and the viscous number
// νΔt/h². A program that prints a table (docs/coupling.md), not a test.
//   imcol_flow_stability [--cases wall,pair,free] [--re 100,300,500,1000,2000] [--cfl 1,0.5,0.35,0.25] [--cells 16,24,32]
//                        [--levels 4] [--limit C]   (--limit: Δt from the step rule flow.cfl = C of coupling/step_rule.hpp)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "flow/solver.hpp"

using namespace imcol::flow;

namespace {

std::vector<double> dlist(const char* s) {
  std::vector<double> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');) v.push_back(std::atof(x.c_str()));
  return v;
}
std::vector<std::string> slist(const char* s) {
  std::vector<std::string> v;
  std::stringstream ss(s);
  for (std::string x; std::getline(ss, x, ',');) v.push_back(x);
  return v;
}

/// Standard drag curve (Clift, Grace & Weber 1978), C_D at Re (Re ≤ 20: 24/Re (1 + 0.1315 Re^(0.82 − 0.05 log Re))).
double cd_standard(double re) {
  const double w = std::log10(re);
  if (re <= 20) return 24 / re * (1 + 0.1315 * std::pow(re, 0.82 - 0.05 * w));
  if (re <= 260) return 24 / re * (1 + 0.1935 * std::pow(re, 0.6305));
  if (re <= 1500) return std::pow(10.0, 1.6435 - 1.1242 * w + 0.1558 * w * w);
  return std::pow(10.0, -2.4571 + 2.5558 * w - 0.9295 * w * w + 0.1049 * w * w * w);
}

struct Outcome {
  bool ok = true;
  long step = 0, steps = 0;
  double courant = 0, f_max = 0;
  std::string why;
};

Outcome run(const std::string& kind, double Re, double dt, int cpd, int levels) {
  Settings s;
  s.nu = 1.0 / Re;
  s.h = 1.0 / cpd;
  s.dt = dt;
  s.levels = levels;
  s.krylov_tol = 1e-8;
  s.krylov_max_iter = 500;
  s.preconditioner_bins = 4;
  s.nr = 2 * static_cast<int>(std::ceil(1.0 * cpd / 2));  // r_max = 1 D, as a coupled run
  std::vector<SphereState> sp;
  double travel = 3.0, u_frame = 0;
  if (kind == "wall") {
    const double lo = -0.75, hi = 4.5 + 1.25;
    s.nz = 4 * static_cast<int>(std::ceil((hi - lo) * cpd / 4));
    s.z_center = 0.5 * (lo + hi);
    s.wall_z = 0.0;
    sp = {{0.5, 4.5, -1.0}};
    travel = 3.5;
  } else if (kind == "pair") {
    // frame of the midpoint: centres at ∓(gap + 1)/2, relative speed U, the midpoint at U/2 (stream −U/2)
    const double sep = 4.5 + 0.25;
    s.nz = 4 * static_cast<int>(std::ceil((sep + 1 + 2.0) * cpd / 4));
    s.z_center = 0.5 * (1.25 - 0.75);
    u_frame = 0.5;
    s.u_inf = -u_frame;
    sp = {{0.5, -2.25, 1.0 - u_frame}, {0.5, 2.25, -u_frame}};
    travel = 3.0;
  } else {
    s.nz = 4 * static_cast<int>(std::ceil((1 + 0.75 + 1.25) * cpd / 4));
    s.z_center = 0.25;
    s.u_inf = -1.0;
    sp = {{0.5, 0.0, 0.0}};
  }
  const double a = 0.5, V = 4.0 / 3.0 * M_PI * a * a * a;
  const double f_ref = 0.5 * M_PI * a * a * cd_standard(Re) + 10 * V;
  Outcome o;
  o.steps = std::lround(travel / dt);
  try {
    Solver solver(s, sp);
    for (long n = 1; n <= o.steps; ++n) {
      for (auto& b : sp) b.z += b.u * dt;
      const StepInfo info = solver.step(sp);
      o.courant = std::max(o.courant, solver.max_courant());
      double f = 0;
      for (double x : info.force) f = std::max(f, std::abs(x));
      if (n > 1) o.f_max = std::max(o.f_max, f);  // step 1 carries the impulsive start
      if (n > 1 && !(f < 10 * f_ref)) {
        o.ok = false;
        o.step = n;
        o.why = "force " + std::to_string(f);
        return o;
      }
    }
  } catch (const std::exception& e) {
    o.ok = false;
    o.why = e.what();
    o.why = o.why.substr(0, 60);
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> cases = {"wall", "pair", "free"};
  std::vector<double> res = {100, 300, 500, 1000, 2000}, cfls = {1, 0.5, 0.35, 0.25}, cells = {16, 24, 32};
  int levels = 4;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : "";
    if (a == "--cases") cases = slist(v), ++i;
    else if (a == "--re") res = dlist(v), ++i;
    else if (a == "--cfl") cfls = dlist(v), ++i;
    else if (a == "--cells") cells = dlist(v), ++i;
    else if (a == "--levels") levels = std::atoi(v), ++i;
    else {
      std::fprintf(stderr, "usage: imcol_flow_stability [--cases wall,pair,free] [--re LIST] [--cfl LIST] [--cells LIST] [--levels L]\n");
      return 2;
    }
  }
  std::printf("%-5s %7s %6s %5s %9s %9s %9s %8s %9s  %s\n", "case", "Re", "cells", "cfl", "nu dt/h2", "Courant", "F_max/Fd", "steps", "outcome", "");
  for (const auto& k : cases)
    for (double cpd : cells)
      for (double Re : res)
        for (double c : cfls) {
          const double h = 1.0 / cpd, dt = c * h;
          const Outcome o = run(k, Re, dt, static_cast<int>(cpd), levels);
          const double fd = 0.5 * M_PI * 0.25 * cd_standard(Re);
          std::printf("%-5s %7g %6g %5g %9.3g %9.3g %9.3g %8ld %9s  %s\n", k.c_str(), Re, cpd, c, dt / Re / (h * h), o.courant, o.f_max / fd,
                      o.ok ? o.steps : o.step, o.ok ? "ok" : "diverged", o.why.c_str());
          std::fflush(stdout);
        }
  return 0;
}
