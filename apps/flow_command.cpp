#include "apps/flow_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include "apps/output_unit.hpp"
#include "apps/plot.hpp"
#include "contact/collision_model.hpp"
#include "contact/formulas.hpp"
#include "core/errors.hpp"
#include "core/report.hpp"
#include "core/timing.hpp"
#include "core/toml_reader.hpp"
#include "flow/cost.hpp"
#include "flow/flow_scene.hpp"
#include "flow/snapshot.hpp"
#include "flow/solver.hpp"

namespace imcol {

namespace {

namespace fs = std::filesystem;
using flow::Solver;

/// f_THR of two spheres on the scene's prescribed paths, from the collision model's own code
/// (CollisionModel::analytic_fluid_force): Schiller–Naumann drag, the asymptotic gap lubrication (the pair default,
/// not the seed's gap law; docs/model-notes.md, "Pairs"), the added mass's
/// velocity part (accelerations taken as zero: the paths are at constant velocity). History forces are left out
/// (they decay after the impulsive start). N along +z on each sphere.
class AnalyticPairForce {
 public:
  explicit AnalyticPairForce(const flow::FlowScene& sc) : model_(collision_scene(sc)) {}
  std::pair<double, double> at(const std::vector<flow::SphereState>& s) const {
    const double gap = s[1].z - s[0].z - s[0].radius - s[1].radius;
    const std::array<double, 4> y = {gap, s[0].u, s[1].z, s[1].u};
    const auto f = model_.analytic_fluid_force(0.0, y, {0.0, 0.0});
    return {f[0], f[1]};
  }

 private:
  static Scene collision_scene(const flow::FlowScene& sc) {
    std::ostringstream t;
    t << std::setprecision(17);
    t << "effects = [\"drag\", \"lubrication\", \"added_mass\", \"elastic\"]\n[fluid]\ndensity = " << sc.density
      << "\nviscosity = " << sc.viscosity << "\n";
    for (const auto& b : sc.spheres)
      t << "[[sphere]]\ndensity = " << 2 * sc.density << "\nyoungs_modulus = 1e9\npoisson_ratio = 0.3\ne_dry = 1.0\ndiameter = "
        << b.diameter << "\nposition = " << b.position << "\nvelocity = " << b.velocity << "\n";
    t << "[drag]\nlaw = \"schiller-naumann\"\n";
    return parse_scene(t.str(), sc.path + " (its f_THR)");
  }
  contact::CollisionModel model_;
};

/// The command-line options replace scene keys; each gets the scene key's check (exit 2 naming the option).
void apply_overrides(flow::FlowScene& sc, const FlowCommandOptions& opt) {
  auto positive = [](const char* option, const char* key, double v) {
    if (!(std::isfinite(v) && v >= 1e-30 && v <= 1e30))
      throw InputError(std::string("command line (") + option + ")", key, "must be a finite number in [1e-30, 1e30] (got " + fmt_number(v) + ")");
  };
  auto in_range = [](const char* option, const char* key, long v, long lo, long hi) {
    if (v < lo || v > hi)
      throw InputError(std::string("command line (") + option + ")", key,
                       "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + std::to_string(v) + ")");
  };
  if (opt.t_end) positive("--t-end", "time.t_end", *opt.t_end), sc.t_end = *opt.t_end, sc.overridden.insert("--t-end");
  if (opt.dt) positive("--dt", "time.dt", *opt.dt), sc.dt = *opt.dt, sc.overridden.insert("--dt");
  if (opt.cells_per_diameter) {
    in_range("--cells", "grid.cells_per_diameter", *opt.cells_per_diameter, 4, 4096);
    sc.cells_per_diameter = static_cast<int>(*opt.cells_per_diameter);
    sc.overridden.insert("--cells");
  }
  if (opt.levels) {
    in_range("--levels", "grid.levels", *opt.levels, 1, 16);
    sc.levels = static_cast<int>(*opt.levels);
    sc.overridden.insert("--levels");
  }
}

/// Memory and wall time estimated before anything is allocated (flow/cost.hpp): beyond half the physical memory
/// the run is refused; beyond an hour it needs --allow-long.
void check_cost(const flow::FlowScene& sc, const FlowCommandOptions& opt) {
  const flow::Settings set = sc.settings();
  std::vector<double> diameters;
  bool moving = false;
  for (const auto& p : sc.spheres) {
    diameters.push_back(p.diameter);
    moving = moving || p.velocity != 0 || p.amplitude != 0;
  }
  const flow::CostEstimate c = flow::estimate_cost(set, diameters, moving);
  const double vertices = c.vertices;
  const std::string where = sc.overridden.empty() ? sc.path : "command line (--cells/--levels)";
  if (const std::string why = flow::memory_refusal(c); !why.empty())
    throw InputError(sc.overridden.count("--cells") || sc.overridden.count("--levels") ? where : sc.path, "grid.cells_per_diameter",
                     "the grid " + why + ": use fewer cells or levels");
  const double steps = std::ceil(sc.t_end / sc.dt - 1e-9);
  const double seconds = steps * c.seconds_per_step;
  if (seconds > 3600 && !opt.allow_long)
    throw InputError(sc.overridden.count("--dt") || sc.overridden.count("--t-end") ? "command line (--dt/--t-end)" : sc.path, "time.dt",
                     "an estimated " + fmt_number(seconds / 3600) + " hours (" + fmt_number(steps) + " steps of " + fmt_number(vertices) +
                         " vertices): raise time.dt, lower time.t_end or the grid, or pass --allow-long to run anyway");
}

}  // namespace

nlohmann::ordered_json run_flow_scene(const std::string& scene_path, const FlowCommandOptions& opt, const fs::path& dir,
                                      const nlohmann::ordered_json& run) {
  flow::FlowScene sc = flow::load_flow_scene(scene_path);
  apply_overrides(sc, opt);
  flow::check_flow_scene(sc);
  check_cost(sc, opt);
  const flow::Settings set = sc.settings();
  const int nb = static_cast<int>(sc.spheres.size());
  const double D = sc.D(), a = 0.5 * D, U = sc.U(), Re = sc.Re(), mu = sc.viscosity, nu = sc.nu();
  const double q = 0.5 * sc.density * U * U * M_PI * a * a;  // dynamic pressure × frontal area
  const double drag_sign = (sc.stream - sc.spheres.front().velocity) >= 0 ? 1.0 : -1.0;
  const double cd_ref = nb == 1 ? flow::standard_drag_coefficient(Re) : NAN;
  const double f_stokes = 6 * M_PI * mu * a * U;
  const long nsteps = std::max(1L, std::lround(std::ceil(sc.t_end / sc.dt - 1e-9)));

  const auto t0 = WallClock::now();
  Solver solver(set, sc.spheres_at(0.0));
  const auto thr = nb == 2 ? std::make_unique<AnalyticPairForce>(sc) : nullptr;
  if (!opt.quiet)
    std::cout << "flow " << sc.name << ": Re = " << Re << ", " << sc.cells_per_diameter << " cells/D, " << set.levels << " levels of "
              << set.nr << " x " << set.nz << " cells, dt = " << sc.dt << " s, " << nsteps << " steps\n";
  {
    double umax = std::abs(sc.stream);
    for (const auto& p : sc.spheres) umax = std::max(umax, std::abs(p.velocity) + 2 * M_PI * p.frequency * std::abs(p.amplitude));
    // explicit (AB2) advection: its step limit matters when it is not swamped by the implicit viscous term over a
    // step, i.e. when both the advective CFL U dt/h and U² dt/ν exceed 1 (at Re 0.1 the latter is ~0.04)
    const double cfl = umax * sc.dt / set.h, visc = umax * umax * sc.dt / nu;
    if (cfl > 1 && visc > 1)
      std::cerr << "imcol: warning: U dt / h = " << cfl << " > 1 and U^2 dt / nu = " << visc
                << " > 1; the explicit (Adams–Bashforth) advection may be unstable\n";
  }
  std::ostringstream hist;
  hist << std::setprecision(10);
  hist << "step,t,wall_s";
  for (int b = 0; b < nb; ++b) hist << ",z" << b + 1 << ",u" << b + 1 << ",F" << b + 1 << ",F_internal" << b + 1;
  hist << ",C_D,C_D_standard,F_stokes_basset,krylov_iterations,slip";
  // a sphere oscillating in fluid at rest: Stokes (1851) / Landau & Lifshitz §24, a ≪ δ not required, A ≪ a
  const auto& s0 = sc.spheres.front();
  const bool osc = nb == 1 && s0.amplitude != 0 && sc.stream == 0 && s0.velocity == 0;
  const double om = 2 * M_PI * s0.frequency, delta = osc ? std::sqrt(2 * nu / om) : 0;
  auto f_osc = [&](double t) {  // F = −6πμa(1 + a/δ)U − 3πa²√(2μρ/ω)(1 + 2a/(9δ)) dU/dt
    const double U = s0.amplitude * om * std::sin(om * t), dU = s0.amplitude * om * om * std::cos(om * t);
    return -6 * M_PI * mu * a * (1 + a / delta) * U - 3 * M_PI * a * a * std::sqrt(2 * mu * sc.density / om) * (1 + 2 * a / (9 * delta)) * dU;
  };
  double osc_err = 0, osc_amp = 0;
  if (osc) hist << ",F_stokes_oscillating";
  if (nb == 2) hist << ",gap_D,F_THR1,F_THR2";
  // one sphere and a wall: f_THR = Brenner's quasi-steady Stokes force −λ(h/a) 6πμaU (no inertia, no history)
  const bool wall1 = nb == 1 && sc.wall_position.has_value();
  auto f_thr_wall = [&](const flow::SphereState& b) {
    const double gap = b.z - b.radius - *sc.wall_position;
    return -contact::brenner_lambda(gap / b.radius) * 6 * M_PI * mu * b.radius * b.u;
  };
  if (sc.wall_position) hist << ",F_wall";
  if (wall1) hist << ",wall_gap_D,F_THR_wall";
  hist << "\n";
  // two spheres: simulated vs reduced-order force at a few gaps (the seed's Fig. 6.4)
  std::vector<double> report_gaps = {1.0, 0.5, 0.25, 0.1, 0.05};
  nlohmann::ordered_json thr_rows = nlohmann::ordered_json::array();
  std::vector<double> cds, times, walls;
  long krylov_total = 0;
  int krylov_max = 0;
  double slip_max = 0, last_cd = NAN, min_gap_seen = INFINITY;
  std::vector<double> last_force(nb, 0.0);
  double last_wall_force = 0;
  int snap = 0;
  long steps_done = 0;
  // impulsive start: compared over 0.8 ≤ νt/a² ≤ 4 (the window of tests/test_flow_drag.cpp)
  const double basset_t0 = 0.8 * a * a / nu, basset_t1 = 4.0 * a * a / nu;
  double basset_err = 0;
  bool basset_any = false;
  for (long n = 1; n <= nsteps; ++n) {
    const double t = n * sc.dt;
    const auto next = sc.spheres_at(t);
    const flow::StepInfo info = solver.step(next);
    steps_done = n;
    const double wall = seconds_since(t0);
    const double cd = drag_sign * info.force[0] / q;
    // impulsively started sphere (Stokes + Basset, t > 0): F = 6πμaU (1 + a/√(πνt))
    const double fsb = f_stokes * (1 + a / std::sqrt(M_PI * nu * t));
    if (nb == 1 && !osc && !sc.wall_position && Re <= 1 && t >= basset_t0 - 1e-12 * basset_t0 && t <= basset_t1 * (1 + 1e-12)) {
      basset_err = std::max(basset_err, std::abs(drag_sign * info.force[0] - fsb) / fsb);
      basset_any = true;
    }
    if (osc && t >= sc.t_end - 1.0 / s0.frequency - 1e-12) {  // the last period; step forces are step averages
      osc_err = std::max(osc_err, std::abs(info.force[0] - f_osc(t - 0.5 * sc.dt)));
      osc_amp = std::max(osc_amp, std::abs(f_osc(t - 0.5 * sc.dt)));
    }
    cds.push_back(cd);
    times.push_back(t);
    walls.push_back(wall);
    last_cd = cd;
    last_force = info.force;
    last_wall_force = info.wall_force;
    krylov_total += info.krylov_iterations;
    krylov_max = std::max(krylov_max, info.krylov_iterations);
    slip_max = std::max(slip_max, info.slip);
    if (n % sc.history_every == 0 || n == nsteps) {
      hist << n << ',' << t << ',' << wall;
      for (int b = 0; b < nb; ++b) hist << ',' << next[b].z << ',' << next[b].u << ',' << info.force[b] << ',' << info.internal[b];
      hist << ',' << cd << ',' << cd_ref << ',' << fsb << ',' << info.krylov_iterations << ',' << info.slip;
      if (osc) hist << ',' << f_osc(t - 0.5 * sc.dt);
      if (nb == 2) {
        const double gap = next[1].z - next[0].z - next[0].radius - next[1].radius;
        const auto [t1, t2] = thr->at(next);
        hist << ',' << gap / D << ',' << t1 << ',' << t2;
      }
      if (sc.wall_position) hist << ',' << info.wall_force;
      if (wall1) hist << ',' << (next[0].z - next[0].radius - *sc.wall_position) / D << ',' << f_thr_wall(next[0]);
      hist << '\n';
    }
    if (nb == 2) {
      const double gap = next[1].z - next[0].z - next[0].radius - next[1].radius;
      while (!report_gaps.empty() && gap <= report_gaps.front() * D) {
        const auto [t1, t2] = thr->at(next);
        // the two spheres' delta kernels (3 h wide each) overlap below a 3-cell gap: f_SIM is not resolved there
        thr_rows.push_back({{"gap_D", gap / D}, {"gap_cells", gap / set.h}, {"resolved", gap >= 3 * set.h}, {"F1", info.force[0]},
                            {"F_THR1", t1}, {"F2", info.force[1]}, {"F_THR2", t2}});
        report_gaps.erase(report_gaps.begin());
      }
    }
    if (wall1) {
      const double gap = next[0].z - next[0].radius - *sc.wall_position;
      while (!report_gaps.empty() && gap <= report_gaps.front() * D) {
        // the sphere's and the wall's delta kernels (3 h wide each) overlap below a 3-cell gap
        thr_rows.push_back({{"gap_D", gap / D}, {"gap_cells", gap / set.h}, {"resolved", gap >= 3 * set.h}, {"F1", info.force[0]},
                            {"F_THR1", f_thr_wall(next[0])}, {"F_wall", info.wall_force}});
        report_gaps.erase(report_gaps.begin());
      }
      if (gap < 3 * set.h && min_gap_seen >= 3 * set.h && !opt.quiet)
        std::cerr << "imcol: warning: at t = " << t << " the wall gap " << gap / D << " D is below 3 cells (h = " << set.h
                  << "): the sphere's and the wall's delta kernels overlap and the force is not resolved (refine the grid)\n";
      min_gap_seen = std::min(min_gap_seen, gap);
      if (sc.min_gap > 0 && gap < sc.min_gap * D) {
        if (!opt.quiet) std::cout << "  t = " << t << ": wall gap " << gap / D << " D < output.min_gap, stop\n";
        break;
      }
    }
    if (!opt.quiet && (n % std::max(1L, nsteps / 10) == 0 || n == nsteps)) {
      std::cout << "  t = " << std::setw(8) << t << "  C_D = " << std::setw(10) << cd;
      for (int b = 0; b < nb; ++b) std::cout << "  F" << b + 1 << " = " << std::setw(11) << info.force[b] << " N";
      if (info.krylov_iterations) std::cout << "  gmres " << info.krylov_iterations;
      std::cout << "  (" << std::fixed << std::setprecision(2) << wall << " s)" << std::defaultfloat << std::setprecision(6) << "\n";
    }
    if (sc.snapshots > 0 && n == (snap + 1) * nsteps / sc.snapshots) {
      write_file_atomic(dir / ("snapshot_" + std::string(snap < 10 ? "0" : "") + std::to_string(snap) + ".csv"), snapshot_csv(solver));
      ++snap;
    }
    if (nb > 1) {
      double gap = INFINITY;
      for (int b = 0; b + 1 < nb; ++b) gap = std::min(gap, next[b + 1].z - next[b].z - 0.5 * (sc.spheres[b].diameter + sc.spheres[b + 1].diameter));
      if (gap < 3 * set.h && min_gap_seen >= 3 * set.h && !opt.quiet)
        std::cerr << "imcol: warning: at t = " << t << " the gap " << gap / D << " D is below 3 cells (h = " << set.h
                  << "): the spheres' delta kernels overlap and the forces are not resolved (refine the grid)\n";
      min_gap_seen = std::min(min_gap_seen, gap);
      if (sc.min_gap > 0 && gap < sc.min_gap * D) break;
    }
  }
  const double wall_total = seconds_since(t0);
  if (sc.snapshots > 0 && snap < sc.snapshots)  // stopped early: one last snapshot
    write_file_atomic(dir / ("snapshot_" + std::string(snap < 10 ? "0" : "") + std::to_string(snap) + ".csv"), snapshot_csv(solver));

  // the standard (steady) drag curve is a reference only for one sphere at constant velocity whose drag has settled:
  // at least 100 steps, the fluid has passed at least 5 D (t U / D >= 5), and the change over the last tenth of the run,
  // read as the tail of an unsteady-Stokes decay C_D = C_inf + c t^(-1/2) (which changes by 5.4 % of what is left over
  // t in [0.9 t_end, t_end]), leaves less than 0.5 % to come: change < 0.027 %
  const std::size_t k90 = cds.size() - 1 - (cds.size() - 1) / 10;
  const double cd_change = cds.empty() ? NAN : std::abs(last_cd - cds[k90]) / std::abs(last_cd);
  const double cd_left = cd_change / (1 / std::sqrt(0.9) - 1);
  const double passed_D = steps_done * sc.dt * U / D;
  const bool settled = nb == 1 && !osc && s0.amplitude == 0 && cds.size() >= 100 && passed_D >= 5 && cd_left < 0.005;
  nlohmann::ordered_json j;
  j["scene"] = sc.path;
  j["name"] = sc.name;
  j["Re"] = Re;
  j["drag_coefficient"] = last_cd;
  j["drag_change_last_tenth_percent"] = 100 * cd_change;
  j["drag_settled"] = settled;
  j["drag_left_to_settle_percent"] = 100 * cd_left;  // extrapolated, t^(-1/2) tail
  j["distance_passed_D"] = passed_D;
  j["drag_coefficient_standard"] = !settled || std::isnan(cd_ref) ? nlohmann::ordered_json() : nlohmann::ordered_json(cd_ref);
  j["drag_error_percent"] = !settled || std::isnan(cd_ref) ? nlohmann::ordered_json() : nlohmann::ordered_json(100 * (last_cd - cd_ref) / cd_ref);
  j["stokes_drag_ratio"] = drag_sign * last_force[0] / f_stokes;  // F / 6πμaU
  if (nb == 1) {
    j["wake_length_D"] = settled && sc.stream != 0 ? nlohmann::ordered_json(solver.wake_length(0) / D) : nlohmann::ordered_json();  // steady runs in a stream only
    // first time after which C_D stays within 3 % of the standard curve
    long k = static_cast<long>(cds.size());
    while (k > 0 && std::abs(cds[k - 1] - cd_ref) <= 0.03 * cd_ref) --k;
    if (settled && k < static_cast<long>(cds.size())) {
      j["time_to_3pct_s"] = times[k];
      j["wall_time_to_3pct_s"] = walls[k];
    } else {
      j["time_to_3pct_s"] = nullptr;
      j["wall_time_to_3pct_s"] = nullptr;
    }
    if (Re <= 1 && !osc && basset_any)
      j["impulsive_start"] = {{"reference", "F = 6 pi mu a U (1 + a / sqrt(pi nu t)), t > 0"},
                              {"window", "0.8 <= nu t / a^2 <= 4"},
                              {"window_t", {basset_t0, std::min(basset_t1, steps_done * sc.dt)}},
                              {"max_rel_error", basset_err}};
  }
  j["forces_N"] = last_force;
  if (nb > 1 || wall1) {
    j["min_gap_D"] = min_gap_seen / D;
    j["gap_resolved"] = min_gap_seen >= 3 * set.h;  // false: the forces below a 3-cell gap are not resolved
  }
  if (nb == 2 || wall1) j["f_sim_vs_f_thr"] = thr_rows;
  if (sc.wall_position) j["wall"] = {{"position", *sc.wall_position}, {"force_N", last_wall_force},
                                      {"f_thr", wall1 ? "Brenner (1961): -lambda(h/a) 6 pi mu a U, quasi-steady Stokes" : ""}};
  if (osc) j["oscillating"] = {{"reference", "F = -6 pi mu a (1 + a/delta) U - 3 pi a^2 sqrt(2 mu rho/omega) (1 + 2a/(9 delta)) dU/dt, at mid-step"},
                               {"delta_over_a", delta / a},
                               {"max_error_last_period_rel_amplitude", osc_amp > 0 ? osc_err / osc_amp : NAN}};
  const auto& L0 = solver.levels().front().g;
  const auto& Lc = solver.levels().back().g;
  j["grid"] = {{"cells_per_diameter", sc.cells_per_diameter},
               {"h", set.h},
               {"levels", set.levels},
               {"nr", set.nr},
               {"nz", set.nz},
               {"finest", {{"r_max", L0.r(L0.nr)}, {"z_min", L0.z0}, {"z_max", L0.z(L0.nz)}}},
               {"coarsest", {{"r_max", Lc.r(Lc.nr)}, {"z_min", Lc.z0}, {"z_max", Lc.z(Lc.nz)}}},
               {"body_points", solver.points().size()}};
  j["dt"] = sc.dt;
  j["theta"] = sc.theta;
  j["steps"] = steps_done;
  j["t_end"] = steps_done * sc.dt;
  j["wall_time_s"] = wall_total;
  j["ms_per_step"] = 1e3 * wall_total / std::max(1L, steps_done);
  j["memory_bytes"] = solver.bytes();
  j["force_solver"] = {{"krylov_tol", sc.krylov_tol}, {"krylov_iterations_mean", steps_done ? double(krylov_total) / steps_done : 0.0},
                       {"krylov_iterations_max", krylov_max}, {"max_slip", slip_max}};
  if (!run.is_null()) j["run"] = run;
  write_file_atomic(dir / "forces.csv", hist.str());
  write_file_atomic(dir / "summary.json", j.dump(2) + "\n");
  return j;
}

int cmd_flow(const std::string& scene_path, const FlowCommandOptions& opt) {
  const flow::FlowScene sc = flow::load_flow_scene(scene_path);
  OutputUnit unit(opt.out, fs::path("out") / sc.name, scene_path);
  const auto j = run_flow_scene(scene_path, opt, unit.dir(), unit.run());
  std::cout << std::setprecision(5);
  std::cout << "Re = " << j["Re"].get<double>() << "  C_D = " << j["drag_coefficient"].get<double>();
  if (!j["drag_coefficient_standard"].is_null())
    std::cout << "  (steady; standard curve " << j["drag_coefficient_standard"].get<double>() << ", error " << std::setprecision(3)
              << j["drag_error_percent"].get<double>() << " %)";
  else if (!j["drag_settled"].get<bool>() && j["forces_N"].size() == 1 && !j.contains("oscillating"))
    std::cout << "  (not settled: changed " << std::setprecision(3) << j["drag_change_last_tenth_percent"].get<double>()
              << " % over the last tenth of the run; not compared with the steady standard curve)";
  std::cout << std::setprecision(5) << "  F/(6 pi mu a U) = " << j["stokes_drag_ratio"].get<double>() << "\n";
  if (j.contains("wake_length_D") && j["wake_length_D"].is_number()) std::cout << "wake length = " << j["wake_length_D"].get<double>() << " D\n";
  if (j.contains("f_sim_vs_f_thr")) {
    for (const auto& r : j["f_sim_vs_f_thr"]) {
      if (r.contains("F_wall"))
        std::cout << "wall gap " << r["gap_D"].get<double>() << " D: F1 = " << r["F1"].get<double>() << " (f_THR Brenner " << r["F_THR1"].get<double>()
                  << ", " << std::setprecision(3) << 100 * (r["F1"].get<double>() / r["F_THR1"].get<double>() - 1) << std::setprecision(5)
                  << " %), wall " << r["F_wall"].get<double>() << " N" << (r["resolved"].get<bool>() ? "" : "  [not resolved: gap below 3 cells]")
                  << "\n";
      else
        std::cout << "gap " << r["gap_D"].get<double>() << " D: F1 = " << r["F1"].get<double>() << " (f_THR " << r["F_THR1"].get<double>()
                  << "), F2 = " << r["F2"].get<double>() << " (f_THR " << r["F_THR2"].get<double>() << ") N"
                  << (r["resolved"].get<bool>() ? "" : "  [not resolved: gap below 3 cells]") << "\n";
    }
  }
  if (j.contains("oscillating"))
    std::cout << "oscillating sphere vs unsteady Stokes (delta/a = " << j["oscillating"]["delta_over_a"].get<double>()
              << "): max error over the last period " << 100 * j["oscillating"]["max_error_last_period_rel_amplitude"].get<double>()
              << " % of the force amplitude\n";
  if (j.contains("impulsive_start"))
    std::cout << "impulsive start vs Stokes + Basset: max relative error " << j["impulsive_start"]["max_rel_error"].get<double>()
              << " for " << j["impulsive_start"]["window_t"][0].get<double>() << " <= t <= "
              << j["impulsive_start"]["window_t"][1].get<double>() << " s (0.8 <= nu t / a^2 <= 4)\n";
  std::cout << "steps " << j["steps"].get<long>() << ", wall " << j["wall_time_s"].get<double>() << " s ("
            << j["ms_per_step"].get<double>() << " ms/step)\n";
  if (opt.plot) {
    std::cout.flush();
    run_plot_script("plot_flow.py", unit, "forces.png");  // also snapshot_NN.png
    if (j.contains("f_sim_vs_f_thr") && !j.contains("wall"))
      run_plot_script("plot_force_vs_gap.py", unit, "forces_vs_gap.png");  // seed Fig. 6.4 (a wall: plot_flow.py draws it)
  }
  unit.commit();
  std::cout << "wrote " << (unit.target() / "forces.csv").string() << ", " << (unit.target() / "summary.json").string() << ", snapshots\n";
  return 0;
}

}  // namespace imcol
