// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Flow scenes (data/scenes/flow/*.toml): spheres on the axis, fixed or on prescribed trajectories, optionally above a
// plane no-slip wall ([wall] position = z_w: the spheres on its +z side, the fluid far away at rest, no stream)
// z(t) = position + velocity·t + amplitude·(1 − cos 2π frequency t) (from rest), optionally in a uniform stream; the grid, time step and solver settings.
// Parsed with toml++; bad input throws InputError naming file:line and key. SI units (any consistent units work).
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/choices.hpp"
#include "flow/solver.hpp"

namespace imcol::flow {

struct FlowSphere {
  double diameter = 0;  // m
  double position = 0;  // z of the centre at t = 0, m
  double velocity = 0;  // prescribed constant velocity along +z, m/s
  double amplitude = 0;  // optional oscillation z += A (1 − cos 2π f t), m (starts from rest)
  double frequency = 0;  // its frequency f, Hz
  int line = 0;          // line of its [[sphere]] table in the scene file (0: unknown)
};

struct FlowScene {
  std::string path, name, description;
  double density = 0, viscosity = 0;  // kg/m³, Pa s
  double stream = 0;                  // uniform stream along +z, m/s
  std::vector<FlowSphere> spheres;
  // optional plane no-slip wall z = wall_position (m), normal to the axis; every sphere stays on its +z side
  std::optional<double> wall_position;
  int line_wall = 0;  // line of the [wall] table (or of its position key)
  // grid (lengths in units of the first sphere's diameter D)
  int cells_per_diameter = 32;
  int levels = 3;
  double r_max = 2, z_min = -2, z_max = 4;  // finest level, D (z relative to the origin, in D)
  // time
  double dt = 0, t_end = 0, theta = 0.5;
  // solver
  double krylov_tol = 1e-10;
  int krylov_max_iter = 1000;
  int krylov_restart = 60;
  double ring_spacing = 1.0;
  bool direct_when_fixed = true;
  bool measure_plans = false;
  // output
  int history_every = 1;  // force history stride, steps
  int snapshots = 1;      // evenly spaced in time, the last at t_end
  FieldsFormat fields_format = FieldsFormat::both;  // snapshot files: CSV, VTK XML (+ flow.pvd), or both
  double min_gap = 0;     // stop when the surface gap of two spheres falls below this, units of D (0 = off)
  // where values came from, for error messages: lines in the file (0: not given), and the command-line options
  // that replaced scene values ("--cells", "--levels", "--dt", "--t-end")
  int line_stream = 0, line_dt = 0, line_t_end = 0;
  std::set<std::string> overridden;
  /// "file:line" (or "file" if line is 0), or "command line (--opt)" if any of opts was overridden.
  std::string where(int line, std::initializer_list<const char*> opts = {}) const;

  double D() const { return spheres.front().diameter; }
  double nu() const { return viscosity / density; }
  /// Reference speed: |stream − sphere 1 velocity|, or sphere 1's oscillation speed amplitude 2πfA if larger.
  double U() const;
  double Re() const { return U() * D() / nu(); }
  /// Solver settings derived from the scene (grid rounded to nr even, nz a multiple of 4).
  Settings settings() const;
  std::vector<SphereState> spheres_at(double t) const;
};

FlowScene load_flow_scene(const std::string& path);
/// Surface gap of sphere i (0-based) to the wall at time t (without its oscillation), m; +inf without a wall.
double wall_gap(const FlowScene& sc, std::size_t i, double t);
/// Relative motion present; dt ≤ t_end; spheres apart at t = 0 and t_end (unless a min_gap stop); every sphere inside
/// the finest level (3 cells clear) at t = 0 and t_end. Throws InputError naming file:line, or the command-line option
/// that caused the problem.
void check_flow_scene(const FlowScene& sc);

/// Standard drag curve, Clift, Grace & Weber (Bubbles, Drops and Particles, 1978, Table 5.2), Re = UD/ν ≤ 1500.
/// Their ranges 0.01 < Re ≤ 20 and 20 ≤ Re ≤ 260 meet at Re = 20; there we use the second formula,
/// C_D = 24/Re (1 + 0.1935 Re^0.6305) = 2.7352 (the first gives 2.7147, 0.75 % lower).
double standard_drag_coefficient(double Re);

}  // namespace imcol::flow
