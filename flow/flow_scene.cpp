// SPDX-License-Identifier: BSD-3-Clause
#include "flow/flow_scene.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "core/errors.hpp"
#include "core/scene_kind.hpp"
#include "core/toml_reader.hpp"

namespace imcol::flow {

namespace {

/// Flow scenes have no --set overrides; a value without a line is the file's own.
struct Reader : TableReader {
  Reader(const toml::table& t, std::string prefix, const std::string& file) : TableReader(t, std::move(prefix), file, file) {}
};

int round_up(double x, int mult) { return std::max(mult, static_cast<int>(std::ceil(x / mult - 1e-9)) * mult); }

}  // namespace

double FlowScene::U() const {
  const auto& s = spheres.front();
  return std::max(std::abs(stream - s.velocity), 2 * M_PI * s.frequency * std::abs(s.amplitude));
}

Settings FlowScene::settings() const {
  Settings s;
  s.nu = nu();
  s.density = density;
  s.dt = dt;
  s.theta = theta;
  s.h = D() / cells_per_diameter;
  // Cell counts in double first: a grid beyond 1e6 cells along an axis is refused naming its key, not converted to an
  // int that overflows.
  auto cells = [&](double n, const char* key) {
    if (!(n <= 1e6))
      throw InputError(path, key, "the finest level would need " + fmt_number(n) + " cells along one axis (more than 1e6): " +
                                      "r_max and z_max - z_min are in diameters, at " + std::to_string(cells_per_diameter) + " cells each");
    return n;
  };
  s.nr = round_up(cells(r_max * cells_per_diameter, "grid.r_max"), 2);
  s.nz = round_up(cells((z_max - z_min) * cells_per_diameter, "grid.z_max"), 4);
  s.levels = levels;
  s.z_center = (z_min * D() + 0.5 * s.nz * s.h);
  s.u_inf = stream;
  s.krylov_tol = krylov_tol;
  s.krylov_max_iter = krylov_max_iter;
  s.krylov_restart = krylov_restart;
  s.ring_spacing = ring_spacing;
  s.direct_when_fixed = direct_when_fixed;
  s.measure_plans = measure_plans;
  s.wall_z = wall_position;
  return s;
}

std::vector<SphereState> FlowScene::spheres_at(double t) const {
  std::vector<SphereState> out;
  for (const auto& s : spheres) {
    const double w = 2 * M_PI * s.frequency;
    out.push_back({0.5 * s.diameter, s.position + s.velocity * t + s.amplitude * (1 - std::cos(w * t)),
                   s.velocity + s.amplitude * w * std::sin(w * t)});
  }
  return out;
}

std::string FlowScene::where(int line, std::initializer_list<const char*> opts) const {
  std::string cl;
  for (const char* o : opts)
    if (overridden.count(o)) cl += (cl.empty() ? "" : ", ") + std::string(o);
  if (!cl.empty()) return "command line (" + cl + ")";
  return line > 0 ? path + ":" + std::to_string(line) : path;
}

double wall_gap(const FlowScene& sc, std::size_t i, double t) {
  if (!sc.wall_position) return INFINITY;
  const auto& p = sc.spheres[i];
  return p.position + p.velocity * t - 0.5 * p.diameter - *sc.wall_position;
}

namespace {

/// Some relative motion, and a time step that ends inside the run.
void check_motion(const FlowScene& sc) {
  if (sc.U() == 0)
    throw InputError(sc.where(sc.line_stream > 0 ? sc.line_stream : sc.spheres.front().line), "stream.velocity",
                     "no relative motion: give a stream or a sphere velocity");
  if (sc.dt > sc.t_end)
    throw InputError(sc.where(sc.line_dt, {"--dt", "--t-end"}), "time.dt",
                     "dt = " + fmt_number(sc.dt) + " exceeds t_end = " + fmt_number(sc.t_end) + " (no step would end inside the run)");
}

/// Neighbours stay apart (gaps are linear in t apart from the oscillations); a min_gap stop ends the run first.
void check_neighbours(const FlowScene& sc) {
  for (std::size_t i = 0; i + 1 < sc.spheres.size(); ++i) {
    const auto &p = sc.spheres[i], &q = sc.spheres[i + 1];
    for (double t : {0.0, sc.t_end}) {
      if (t > 0 && sc.min_gap > 0) continue;
      const double gap = (q.position + q.velocity * t) - (p.position + p.velocity * t) - 0.5 * (p.diameter + q.diameter) -
                         (t > 0 ? std::abs(p.amplitude) + std::abs(q.amplitude) : 0.0);
      if (gap <= 0) {
        if (t == 0)
          throw InputError(sc.where(q.line), "sphere[" + std::to_string(i + 1) + "]",
                           "sphere " + std::to_string(i + 2) + " overlaps sphere " + std::to_string(i + 1) +
                               " at t = 0 or is out of order (list the spheres by increasing position)");
        throw InputError(sc.where(q.line, {"--t-end"}), "sphere[" + std::to_string(i + 1) + "]",
                         "spheres " + std::to_string(i + 1) + " and " + std::to_string(i + 2) + " would overlap by t = " + fmt_number(t) +
                             " (shorten time.t_end or set output.min_gap)");
      }
    }
  }
}

/// The finest level's extent (m) and spacing.
struct FinestBox {
  double zlo, zhi, rhi, h;
};

FinestBox finest_box(const FlowScene& sc) {
  const Settings s = sc.settings();
  return {s.z_center - 0.5 * s.nz * s.h, s.z_center + 0.5 * s.nz * s.h, s.nr * s.h, s.h};
}

/// A wall: no stream, inside the finest level 3 cells clear, every sphere on its +z side over the run.
void check_wall(const FlowScene& sc, const FinestBox& box) {
  const double zlo = box.zlo, zhi = box.zhi;
  const double zw = *sc.wall_position;
  if (sc.stream != 0)
    throw InputError(sc.where(sc.line_stream), "stream.velocity",
                     "a stream cannot be combined with a [wall] (the fluid far away is at rest with the wall; move the sphere instead)");
  if (zw < zlo + 3 * box.h || zw > zhi - 3 * box.h)
    throw InputError(sc.where(sc.line_wall, {"--cells"}), "wall.position",
                     "the wall z = " + fmt_number(zw) + " must lie inside the finest grid (z in [" + fmt_number(zlo) + ", " + fmt_number(zhi) +
                         "], 3 cells clear)");
  for (std::size_t i = 0; i < sc.spheres.size(); ++i) {
    const auto& p = sc.spheres[i];
    for (double t : {0.0, sc.t_end}) {
      if (t > 0 && sc.min_gap > 0) continue;
      const double gap = wall_gap(sc, i, t) - (t > 0 ? std::abs(p.amplitude) : 0.0);
      if (gap <= 0)
        throw InputError(t > 0 ? sc.where(p.line, {"--t-end"}) : sc.where(p.line), "sphere[" + std::to_string(i) + "]",
                         t > 0 ? "sphere " + std::to_string(i + 1) + " would reach the wall by t = " + fmt_number(t) +
                                     " (shorten time.t_end or set output.min_gap)"
                               : "sphere " + std::to_string(i + 1) + " touches the wall or is below it at t = 0 (spheres go on the wall's +z side)");
    }
  }
}

/// Every sphere inside the finest level over the whole run, 3 cells clear of its edges.
void check_inside_grid(const FlowScene& sc, const FinestBox& box) {
  const double zlo = box.zlo, zhi = box.zhi, rhi = box.rhi;
  for (std::size_t i = 0; i < sc.spheres.size(); ++i) {
    const auto& p = sc.spheres[i];
    const double a = 0.5 * p.diameter;
    for (double t : {0.0, sc.t_end}) {
      const double z = p.position + p.velocity * t + p.amplitude, A = std::abs(p.amplitude);
      if (z - a - A < zlo + 3 * box.h || z + a + A > zhi - 3 * box.h || a > rhi - 3 * box.h)
        throw InputError(t > 0 ? sc.where(p.line, {"--cells", "--t-end"}) : sc.where(p.line, {"--cells"}),
                         "sphere[" + std::to_string(i) + "]",
                         "sphere outside the finest grid at t = " + fmt_number(t) + " (grid z in [" + fmt_number(zlo) + ", " + fmt_number(zhi) +
                             "], r < " + fmt_number(rhi) + ", 3 cells clear)");
    }
  }
}

}  // namespace

void check_flow_scene(const FlowScene& sc) {
  check_motion(sc);
  check_neighbours(sc);
  const FinestBox box = finest_box(sc);
  if (sc.wall_position) check_wall(sc, box);
  check_inside_grid(sc, box);
}

namespace {

/// [fluid] (required): density and viscosity.
void read_fluid(Reader& top, FlowScene& sc) {
  const std::string& path = sc.path;
  const toml::table* fluid = top.table("fluid");
  if (!fluid) throw InputError(path, "fluid", "missing (required table)");
  Reader r(*fluid, "fluid", path);
  sc.density = r.required_positive("density");
  sc.viscosity = r.required_positive("viscosity");
  r.finish();
}

/// [stream]: the uniform stream.
void read_stream(Reader& top, FlowScene& sc) {
  const std::string& path = sc.path;
  if (const toml::table* st = top.table("stream")) {
    Reader r(*st, "stream", path);
    sc.stream = r.number("velocity", 0.0);
    const toml::node* v = st->get("velocity");
    sc.line_stream = static_cast<int>((v ? v->source() : st->source()).begin.line);
    r.finish();
  }
}

/// [wall]: the plane wall's position.
void read_wall(Reader& top, FlowScene& sc) {
  const std::string& path = sc.path;
  if (const toml::table* w = top.table("wall")) {
    Reader r(*w, "wall", path);
    const toml::node* v = w->get("position");
    sc.line_wall = static_cast<int>((v ? v->source() : w->source()).begin.line);
    if (!v) throw InputError(sc.where(sc.line_wall), "wall.position", "missing (the wall's z, m; spheres on its +z side)");
    sc.wall_position = r.number("position", 0.0);
    if (!std::isfinite(*sc.wall_position)) r.fail("position", "must be a finite number");
    r.finish();
  }
}

/// [[sphere]] (at least one): size, position and prescribed motion.
void read_spheres(Reader& top, FlowScene& sc) {
  const std::string& path = sc.path;
  const toml::node* sn = top.node("sphere");
  if (!sn || !sn->is_array_of_tables() || sn->as_array()->empty())
    throw InputError(top.where(sn), "sphere", "give at least one [[sphere]] table");
  int k = 0;
  for (const auto& el : *sn->as_array()) {
    ++k;
    Reader r(*el.as_table(), "sphere[" + std::to_string(k - 1) + "]", path);
    FlowSphere s;
    s.line = static_cast<int>(el.source().begin.line);
    s.diameter = r.required_positive("diameter");
    s.position = r.number("position", 0.0);
    s.velocity = r.number("velocity", 0.0);
    s.amplitude = r.number("amplitude", 0.0);
    s.frequency = r.number("frequency", 0.0);
    if (s.frequency < 0) r.fail("frequency", "must be >= 0");
    if (s.amplitude != 0 && s.frequency == 0) r.fail("amplitude", "an oscillation needs frequency > 0");
    r.finish();
    sc.spheres.push_back(s);
  }
}

/// [grid]: cells per diameter, levels and the finest level's extent.
void read_grid(Reader& top, FlowScene& sc) {
  const std::string& path = sc.path;
  if (const toml::table* g = top.table("grid")) {
    Reader r(*g, "grid", path);
    const long cpd = r.integer("cells_per_diameter", sc.cells_per_diameter);
    if (cpd < 4 || cpd > 4096) r.fail("cells_per_diameter", "must be in [4, 4096] (got " + std::to_string(cpd) + ")");
    sc.cells_per_diameter = static_cast<int>(cpd);
    const long lv = r.integer("levels", sc.levels);
    if (lv < 1 || lv > 16) r.fail("levels", "must be in [1, 16] (got " + std::to_string(lv) + ")");
    sc.levels = static_cast<int>(lv);
    sc.r_max = r.number("r_max", sc.r_max);
    r.positive("r_max", sc.r_max);
    sc.z_min = r.number("z_min", sc.z_min);
    sc.z_max = r.number("z_max", sc.z_max);
    if (!(sc.z_max > sc.z_min)) r.fail("z_max", "must exceed grid.z_min");
    r.finish();
  }
}

/// [time] (required): dt, t_end, theta.
void read_time(Reader& top, FlowScene& sc) {
  const std::string& path = sc.path;
  const toml::table* tt = top.table("time");
  if (!tt) throw InputError(path, "time", "missing (required table with dt and t_end)");
  Reader r(*tt, "time", path);
  sc.dt = r.required_positive("dt");
  sc.t_end = r.required_positive("t_end");
  sc.line_dt = static_cast<int>(tt->get("dt")->source().begin.line);
  sc.line_t_end = static_cast<int>(tt->get("t_end")->source().begin.line);
  sc.theta = r.number("theta", sc.theta);
  if (!(sc.theta >= 0.5 && sc.theta <= 1)) r.fail("theta", "must be in [0.5, 1] (0.5 = Crank–Nicolson)");
  r.finish();
}

/// [flow]: the kernel's solver settings, as in collision scenes ([solver] is the ODE solver there, refused here).
void read_flow_settings(Reader& top, FlowScene& sc) {
  const std::string& path = sc.path;
  if (top.has("solver"))
    top.fail("solver", "the flow kernel's settings (krylov_tol, krylov_max_iter, krylov_restart, ring_spacing, "
                       "direct_when_fixed, fft_plan) are in the [flow] table ([solver] is the ODE solver of collision scenes)");
  if (const toml::table* so = top.table("flow")) {
    Reader r(*so, "flow", path);
    sc.krylov_tol = r.number("krylov_tol", sc.krylov_tol);
    r.positive("krylov_tol", sc.krylov_tol);
    if (sc.krylov_tol >= 1) r.fail("krylov_tol", "must be < 1");
    const long it = r.integer("krylov_max_iter", sc.krylov_max_iter);
    if (it < 1) r.fail("krylov_max_iter", "must be >= 1");
    sc.krylov_max_iter = static_cast<int>(it);
    const long rs = r.integer("krylov_restart", sc.krylov_restart);
    if (rs < 1 || rs > 1000) r.fail("krylov_restart", "must be in [1, 1000]");
    sc.krylov_restart = static_cast<int>(rs);
    sc.ring_spacing = r.number("ring_spacing", sc.ring_spacing);
    if (!(sc.ring_spacing >= 0.25 && sc.ring_spacing <= 4)) r.fail("ring_spacing", "must be in [0.25, 4] (units of h)");
    sc.direct_when_fixed = r.boolean("direct_when_fixed", sc.direct_when_fixed);
    if (auto p = r.string("fft_plan")) {
      if (*p != "estimate" && *p != "measure") r.fail("fft_plan", "unknown choice '" + *p + "' (expected estimate | measure)");
      sc.measure_plans = *p == "measure";
    }
    r.finish();
  }
}

/// [output]: history stride, snapshots and their format, min_gap stop.
void read_output(Reader& top, FlowScene& sc) {
  const std::string& path = sc.path;
  if (const toml::table* o = top.table("output")) {
    Reader r(*o, "output", path);
    const long e = r.integer("history_every", sc.history_every);
    if (e < 1) r.fail("history_every", "must be >= 1");
    sc.history_every = static_cast<int>(e);
    const long s = r.integer("snapshots", sc.snapshots);
    if (s < 0 || s > 1000) r.fail("snapshots", "must be in [0, 1000]");
    sc.snapshots = static_cast<int>(s);
    r.choice("fields_format", sc.fields_format);
    sc.min_gap = r.number("min_gap", 0.0);
    if (sc.min_gap < 0) r.fail("min_gap", "must be >= 0");
    r.finish();
  }
}

}  // namespace

FlowScene load_flow_scene(const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(read_scene_file(path), path);
  } catch (const toml::parse_error& e) {
    throw InputError(path + ":" + std::to_string(e.source().begin.line), "", "TOML syntax error: " + std::string(e.description()));
  }
  if (scene_kind(root) == SceneKind::collision) throw InputError(path, "", other_scene_kind_message(SceneKind::collision));
  FlowScene sc;
  sc.path = path;
  Reader top(root, "", path);
  sc.name = top.string("name").value_or(std::filesystem::path(path).stem().string());
  sc.description = top.string("description").value_or("");
  read_fluid(top, sc);
  read_stream(top, sc);
  read_wall(top, sc);
  read_spheres(top, sc);
  read_grid(top, sc);
  read_time(top, sc);
  read_flow_settings(top, sc);
  read_output(top, sc);
  top.finish();
  check_flow_scene(sc);
  return sc;
}

double standard_drag_coefficient(double Re) {
  if (!(Re > 0)) return NAN;
  const double w = std::log10(Re);
  if (Re <= 0.01) return 3.0 / 16.0 + 24.0 / Re;
  if (Re < 20) return 24.0 / Re * (1 + 0.1315 * std::pow(Re, 0.82 - 0.05 * w));
  if (Re <= 260) return 24.0 / Re * (1 + 0.1935 * std::pow(Re, 0.6305));
  if (Re <= 1500) return std::pow(10.0, 1.6435 - 1.1242 * w + 0.1558 * w * w);
  return NAN;
}

}  // namespace imcol::flow
