#include "apps/simulate.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <iostream>
#include <tuple>
#include <unistd.h>

#include "contact/collision_model.hpp"
#include "core/measure.hpp"
#include "core/report.hpp"
#include "coupling/flow_coupling.hpp"
#include "integrators/integrator.hpp"

namespace imcol {

namespace {

using contact::CollisionModel;
using contact::Evaluation;

/// Samples the solution into trajectory rows, evaluating the force terms with the phase in force.
class Recorder : public Observer {
 public:
  Recorder(CollisionModel& model, const Scene& sc, bool progress) : model_(model), sc_(sc), progress_(progress && ::isatty(2)) {
    const bool pair = model.n_spheres() == 2;
    columns_ = {"t", "z1", "u1"};
    if (model.has_target()) columns_.push_back("gap");
    if (pair) {
      columns_.push_back("z2");
      columns_.push_back("u2");
    }
    if (model.has_target()) columns_.push_back("u_rel");
    for (int m = 1; m <= static_cast<int>(model.n_spheres()); ++m) {
      const std::string k = std::to_string(m);
      if (sc.has(Effect::drag)) columns_.push_back("f_drag" + k);
      if (sc.has(Effect::lubrication)) columns_.push_back("f_lub" + k);
      if (sc.has(Effect::added_mass)) columns_.push_back("f_am" + k);
      if (sc.has(Effect::elastic)) columns_.push_back("f_contact" + k);
      if (sc.has(Effect::gravity)) columns_.push_back("f_grav" + k);
      if (sc.has(Effect::history)) columns_.push_back("f_hist" + k);
      if (sc.has(Effect::flow)) {
        columns_.push_back("f_sim" + k);
        columns_.push_back("f_thr" + k);
      }
      columns_.push_back("a" + k);
    }
    if (sc.has(Effect::flow)) columns_.push_back("H");
    columns_.push_back("event");
  }

  void sample(double t, std::span<const double> y, bool at_event) override {
    const Evaluation ev = model_.evaluate(t, y);
    std::vector<double> r = {t, ev.z[0], ev.u[0]};
    const bool pair = model_.n_spheres() == 2;
    if (model_.has_target()) r.push_back(ev.gap);
    if (pair) {
      r.push_back(ev.z[1]);
      r.push_back(ev.u[1]);
    }
    if (model_.has_target()) r.push_back(ev.u_rel);
    for (std::size_t m = 0; m < model_.n_spheres(); ++m) {
      const auto& f = ev.f[m];
      if (sc_.has(Effect::drag)) r.push_back(f.drag);
      if (sc_.has(Effect::lubrication)) r.push_back(f.lubrication);
      if (sc_.has(Effect::added_mass)) r.push_back(f.added_mass);
      if (sc_.has(Effect::elastic)) r.push_back(f.contact);
      if (sc_.has(Effect::gravity)) r.push_back(f.gravity);
      if (sc_.has(Effect::history)) r.push_back(f.history);
      if (sc_.has(Effect::flow)) {
        r.push_back(f.f_sim);
        r.push_back(f.f_thr);
      }
      r.push_back(f.accel);
      max_history_ = std::max(max_history_, std::abs(f.history));
    }
    if (sc_.has(Effect::flow)) r.push_back(ev.H);
    r.push_back(at_event ? 1.0 : 0.0);
    rows_.push_back(std::move(r));
    model_.observe(t, ev);  // may end the run: at rest on the wall, or moving with its partner
    if (progress_) show_progress(t);
    if (model_.has_target()) {
      min_gap_ = std::min(min_gap_, ev.gap);
      max_force_ = std::max(max_force_, std::abs(ev.f[0].contact));
    }
  }

  /// Clears the progress line, if one was shown.
  void finish_progress() {
    if (shown_) std::cerr << "\r" << std::string(96, ' ') << "\r" << std::flush;
  }

  std::vector<std::string> columns_;
  std::vector<std::vector<double>> rows_;
  double min_gap_ = INFINITY, max_force_ = 0, max_history_ = 0;

 private:
  void show_progress(double t) {
    const auto now = std::chrono::steady_clock::now();
    const double run = std::chrono::duration<double>(now - start_).count();
    if (run < 2.0 || std::chrono::duration<double>(now - last_).count() < 0.5) return;
    last_ = now;
    shown_ = true;
    const double t_end = sc_.solver.t_end;
    const double left = t > 0 ? run * (t_end - t) / t : 0.0;  // at most: the run may stop once e is measured
    std::cerr << "\r  t = " << std::setprecision(4) << t << " s of t_end " << t_end << " s (" << std::fixed << std::setprecision(1)
              << 100 * t / t_end << " %), " << run << " s elapsed, at most " << left << " s left   " << std::defaultfloat
              << std::flush;
  }

  CollisionModel& model_;
  const Scene& sc_;
  bool progress_ = false, shown_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_ = start_;
};

nlohmann::ordered_json or_null(const std::optional<double>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

/// When the relative velocity of a pair first vanished: the first loading -> unloading switch, or the stopped approach.
std::optional<double> group_moment(const CollisionModel& model) {
  for (const auto& ev : model.events())
    if (ev.name.rfind("u_rel=0", 0) == 0) return ev.t;
  return model.t_closest();
}

}  // namespace

RunResult simulate(const Scene& sc, bool progress) {
  const auto setup_start = std::chrono::steady_clock::now();
  CollisionModel model(sc);
  const auto wall_start = std::chrono::steady_clock::now();
  const double setup = std::chrono::duration<double>(wall_start - setup_start).count();
  Recorder rec(model, sc, progress);
  IntegratorSettings st;
  st.method = sc.solver.integrator;
  st.rtol = sc.solver.rtol;
  st.atol = sc.solver.atol;
  st.output_dt = sc.output.dt;
  st.max_steps = sc.solver.max_steps;
  st.linear_solver = sc.solver.linear_solver;
  st.krylov_tol = sc.solver.krylov_tol;
  std::unique_ptr<coupling::FlowCoupling> coupled;
  SolverStats stats;
  try {
    if (sc.has(Effect::flow)) {
      coupled = std::make_unique<coupling::FlowCoupling>(model, sc);
      stats = coupled->run(st, rec);
    } else {
      stats = integrate(model, st, rec);
    }
  } catch (...) {
    rec.finish_progress();
    throw;
  }
  rec.finish_progress();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  RunResult res;
  res.scene = sc;
  res.columns = rec.columns_;
  res.rows = std::move(rec.rows_);

  // Columns for the fits.
  std::vector<double> t, z1, z2;
  const bool pair = model.n_spheres() == 2;
  for (const auto& r : res.rows) {
    t.push_back(r[0]);
    z1.push_back(r[1]);
    z2.push_back(pair ? r[4] : 0.0);
  }
  const double t_final = t.empty() ? 0.0 : t.back();
  const double W = sc.measure.window;
  std::vector<std::string> warnings;

  auto& s = res.summary;
  s["scene"] = sc.name;
  s["scene_file"] = sc.path;
  s["configuration"] = !model.has_target() ? "free sphere" : (model.has_wall() ? "sphere-wall" : "sphere-sphere");

  std::optional<double> e, e_inst, St, St_62, Re, U_G, t_group;
  // St in the reported convention: eq. (6.2) for a wall, half of it for a pair (seed Table 6.1).
  auto stokes = [&](double u_rel) {
    const double st62 = stokes_number(model.m_star(), u_rel, sc.fluid->viscosity, model.a_star());
    return std::pair{pair ? st62 / 2 : st62, st62};
  };
  std::optional<double> u_i1, u_i2, u_r1, u_r2;
  double fit_window = W;
  bool separated = model.t_separation().has_value();
  const bool collided = model.t_contact() || model.t_closest();  // reached contact or a closest approach
  // A longer solver.t_end would change e only if an approach is under way or gravity can start one.
  const bool can_approach = model.initial_u_rel() > 0 || sc.has(Effect::gravity);
  bool t_end_too_short = model.has_target() && !collided && can_approach;
  if (model.has_target() && !collided) {
    if (can_approach)
      warnings.push_back("no collision by t_end: the gap never reached delta_ss and the approach never stopped; e is undefined");
    else
      warnings.push_back("no collision: the spheres are not approaching (U_rel(0) <= 0, no gravity), so no t_end gives one; e is undefined");
  }
  if (model.has_target() && collided) {
    // Approach window ends at the first δ_SS crossing, or at the closest approach without contact.
    const double t_ref = model.t_contact().value_or(*model.t_closest());
    // A short approach shortens both windows alike, so that they stay symmetric in time.
    const bool in_contact = model.started_in_contact();
    const double Wfit = in_contact ? W : std::min(W, t_ref);
    if (in_contact) {
      // No approach to fit: the impact velocities are the initial ones.
      u_i1 = sc.spheres[0].velocity;
      u_i2 = pair ? sc.spheres[1].velocity : 0.0;
      std::ostringstream os;
      os << "started inside the contact zone: the zone is shortened to the initial gap (" << model.delta_ss_m()
         << " m) and the impact velocities are the initial ones";
      warnings.push_back(os.str());
    } else {
      if (Wfit < W) warnings.push_back("the approach lasted less than the fit window: both fits use windows of the approach's length");
      auto f1 = fit_line_continuous(t, z1, t_ref - Wfit, t_ref);
      auto f2 = pair ? fit_line_continuous(t, z2, t_ref - Wfit, t_ref) : std::optional<LineFit>(LineFit{});
      if (f1 && f2) {
        u_i1 = f1->slope;
        u_i2 = f2->slope;
      }
    }
    // Rebound window: from the separation, or the last window of the run.
    const double t_post = separated ? *model.t_separation() : std::max(t_ref, t_final - Wfit);
    auto g1 = fit_line_continuous(t, z1, t_post, t_post + Wfit);
    auto g2 = pair ? fit_line_continuous(t, z2, t_post, t_post + Wfit) : std::optional<LineFit>(LineFit{});
    fit_window = Wfit;
    if (g1 && g2) {
      u_r1 = g1->slope;
      u_r2 = g2->slope;
    }
    if (separated && t_final < *model.t_separation() + W * (1 - 1e-9)) {
      t_end_too_short = true;
      warnings.push_back("t_end cut the rebound fit window short");
    }
    if (u_i1 && u_r1) {
      if (separated) e = restitution(*u_i1, *u_i2, *u_r1, *u_r2);
      else {
        e = 0.0;  // never separated
        const double closing = *u_r1 - *u_r2;  // > 0: still approaching over the last window
        if (pair) {
          // Group velocity: the pair's centre-of-mass velocity, when the two move together.
          const double m1 = model.mass(0), m2 = model.mass(1);
          const double ug = (m1 * *u_r1 + m2 * *u_r2) / (m1 + m2);
          if (std::abs(closing) <= 0.1 * std::abs(ug)) {
            // U_G at a stated moment, not at t_end (the pair keeps slowing down under drag): the centre-of-mass
            // velocity when the relative velocity first vanished (the loading -> unloading switch after contact,
            // or the stopped approach without contact), where the two spheres move together.
            t_group = group_moment(model);
            if (t_group) {
              for (const auto& row : res.rows)
                if (row[0] == *t_group) {
                  U_G = (m1 * row[2] + m2 * row[5]) / (m1 + m2);
                  break;
                }
            }
          } else {
            std::ostringstream os;
            os << "no group velocity: the spheres' velocities still differ by " << closing
               << " m/s over the last window (centre-of-mass velocity " << ug << " m/s)";
            warnings.push_back(os.str());
          }
        }
        if (model.t_contact() && -closing > 1e-3 * std::abs(*u_i1 - *u_i2)) {
          t_end_too_short = true;
          std::ostringstream os;
          os << "no separation by t_end, but the gap was growing at " << -closing
             << " m/s over the last window (e = 0 by definition; a longer solver.t_end may show a rebound)";
          warnings.push_back(os.str());
        }
      }
      if (sc.fluid) {
        const double u_rel = *u_i1 - *u_i2;
        std::tie(St, St_62) = stokes(u_rel);
        Re = sc.fluid->density * 2 * model.radius(0) * u_rel / sc.fluid->viscosity;
      }
    }
    if (model.u_rel_instant_in()) {
      if (model.u_rel_instant_out()) e_inst = -*model.u_rel_instant_out() / *model.u_rel_instant_in();
      else if (!separated) e_inst = 0.0;
    }
    if (!e_inst && model.t_contact())
      warnings.push_back("e_instant: the gap did not cross measure.instant_gap inward and outward before t_end");
  }

  if (e && sc.has(Effect::elastic) && *e > model.e_dry() * (1 + 1e-9)) {
    // More elastic than the solids alone: energy was created. Known for the seed's per-sphere added mass with unequal spheres.
    std::ostringstream os;
    os << "e = " << *e << " exceeds the dry restitution e_dry = " << model.e_dry()
       << ": energy was created, by integration error (tighten solver.rtol, now " << sc.solver.rtol << ")";
    if (pair && sc.has(Effect::added_mass) && sc.added_mass.model == "seed")
      os << " or by the seed's per-sphere added mass (6.8), which is not conservative for unequal spheres (use added_mass.model = \"lagrangian\")";
    warnings.push_back(os.str());
  }
  if (e && (sc.solver.rtol > 1e-4 || sc.solver.atol > 1e-4)) {
    // Measured (docs/measurements.md): with the contact step bound, rtol = atol = 1e-3 gives e within 1.5 %, 1e-2 within 20 %.
    std::ostringstream os;
    os << "loose tolerances (rtol " << sc.solver.rtol << ", atol " << sc.solver.atol
       << "): e may be off by several per cent (up to 20 % at 1e-2 on the shipped scenes); use rtol and atol <= 1e-4 for e to ~1e-3";
    warnings.push_back(os.str());
  }
  s["e"] = or_null(e);
  s["e_instant"] = or_null(e_inst);
  s["e_instant_gap_m"] = sc.measure.instant_gap * 2 * model.radius(0);
  s["St"] = or_null(St);
  if (pair) {
    s["St_convention"] = "seed Table 6.1: half of eq. (6.2); (1/9)(rho_harm/rho_f) Re_rel for equal spheres";
    s["St_B_eq_6_2"] = or_null(St_62);
  } else {
    s["St_convention"] = "m U / (6 pi mu a^2)";
  }
  s["Re"] = or_null(Re);
  if (sc.fluid && model.has_target()) s["St_initial"] = stokes(model.initial_u_rel()).first;  // nominal, same convention
  s["separated"] = separated;
  // The run ended because the pair came to rest (MODEL.md §3 has no event for it; see CollisionModel::observe).
  s["at_rest_since_s"] = or_null(model.t_at_rest());
  s["t_end_too_short"] = t_end_too_short;
  if (model.has_target()) s["final_phase"] = contact::to_string(model.phase());
  s["contacts"] = model.contacts();
  s["velocities_m_s"] = {{"U_i1", or_null(u_i1)}, {"U_i2", or_null(u_i2)}, {"U_r1", or_null(u_r1)}, {"U_r2", or_null(u_r2)}};
  s["fit_window_s"] = fit_window;
  s["min_gap_m"] = model.has_target() ? nlohmann::ordered_json(rec.min_gap_) : nlohmann::ordered_json(nullptr);
  s["max_contact_force_N"] = rec.max_force_;
  s["group_velocity_m_s"] = or_null(U_G);
  if (U_G) s["group_velocity_at_s"] = *t_group;
  if (sc.has(Effect::history)) s["max_history_force_N"] = rec.max_history_;  // at the output samples and events
  if (!res.rows.empty()) {
    s["u1_final_m_s"] = res.rows.back()[2];
    if (pair) s["u2_final_m_s"] = res.rows.back()[5];
  }
  if (model.has_target() && sc.has(Effect::elastic)) {
    s["contact"] = {{"t_contact_s", or_null(model.t_contact())},
                    {"t_separation_s", or_null(model.t_separation())},
                    {"impact_speed_m_s", model.t_contact() ? nlohmann::ordered_json(model.impact_speed()) : nullptr},
                    {"W_o_N", model.t_contact() ? nlohmann::ordered_json(model.W_o()) : nullptr},
                    {"beta", model.t_contact() ? nlohmann::ordered_json(model.beta()) : nullptr},
                    {"e_dry", model.e_dry()},
                    {"delta_ss_m", model.delta_ss_m()}};
  }
  nlohmann::ordered_json eff = nlohmann::ordered_json::array();
  for (Effect x : sc.effects) eff.push_back(to_string(x));
  s["effects"] = eff;
  nlohmann::ordered_json mod = nlohmann::ordered_json::object();
  for (const auto& [k, v] : model.choices()) mod[k] = v;
  s["model"] = mod;
  nlohmann::ordered_json sol = {{"integrator", st.method}, {"linear_solver", stats.linear_solver},
                                {"rtol", st.rtol}, {"atol", st.atol},
                                {"absolute_tolerances", model.absolute_tolerances(st.atol)},
                                {"state", model.component_names()}, {"max_step_s", model.max_step()},
                                {"t_final_s", t_final}};
  for (const auto& [k, v] : stats.as_map()) sol[k] = v;
  s["solver"] = sol;
  nlohmann::ordered_json ev = nlohmann::ordered_json::array();
  for (const auto& x : model.events()) ev.push_back({{"t", x.t}, {"event", x.name}, {"gap_m", x.gap}, {"u_rel_m_s", x.u_rel}});
  s["events"] = ev;
  s["warnings"] = warnings;
  if (coupled) {
    const auto& fs = coupled->stats();
    const double ms = fs.steps ? 1e3 * fs.flow_seconds / fs.steps : 0.0;
    s["flow"] = {{"grid", {{"cells_per_diameter", fs.cells_per_diameter}, {"h_m", fs.h}, {"nr", fs.nr}, {"nz", fs.nz},
                           {"levels", fs.levels}, {"memory_MB", fs.bytes / 1e6}}},
                 {"dt_s", fs.dt}, {"start", to_string(sc.flow.start)}, {"start_up_steps", fs.pre_steps},
                 {"force_in_step", to_string(sc.flow.force_in_step)}, {"steps", fs.steps}, {"ms_per_step", ms},
                 {"krylov_iterations", fs.krylov_iterations},
                 {"krylov_iterations_per_step", fs.steps ? double(fs.krylov_iterations) / fs.steps : 0.0},
                 {"max_krylov_iterations", fs.max_krylov_iterations}, {"max_krylov_residual", fs.max_krylov_residual},
                 {"max_slip_m_s", fs.max_slip}, {"min_gap_clamped_steps", fs.min_gap_clamped_steps},
                 {"frame_travel_m", fs.frame_travel}, {"start_up_time_s", fs.pre_seconds},
                 {"flow_time_s", fs.flow_seconds}, {"ode_time_s", fs.ode_seconds},
                 {"flow_share", wall > 0 ? fs.flow_seconds / wall : 0.0}, {"ode_share", wall > 0 ? fs.ode_seconds / wall : 0.0}};
    for (const auto& snap : coupled->snapshots()) res.files.push_back({snap.name + ".csv", snap.csv});
  }
  s["wall_time_s"] = wall;
  s["setup_time_s"] = setup;  // model construction, incl. one-off lookup tables
  return res;
}

void write_outputs(const RunResult& r, const std::filesystem::path& dir) {
  std::ostringstream csv;
  csv << std::setprecision(12);
  for (std::size_t i = 0; i < r.columns.size(); ++i) csv << (i ? "," : "") << r.columns[i];
  csv << "\n";
  for (const auto& row : r.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) csv << (i ? "," : "") << row[i];
    csv << "\n";
  }
  write_file_atomic(dir / "trajectory.csv", csv.str());
  for (const auto& [name, content] : r.files) write_file_atomic(dir / name, content);
  write_file_atomic(dir / "summary.json", r.summary.dump(2) + "\n");
}

std::string human_summary(const RunResult& r) {
  const auto& s = r.summary;
  std::ostringstream os;
  auto num = [](const nlohmann::ordered_json& j, int prec = 4) {
    if (j.is_null()) return std::string("n/a");
    std::ostringstream o;
    o << std::setprecision(prec) << j.get<double>();
    return o.str();
  };
  os << "scene " << s["scene"].get<std::string>() << " (" << s["configuration"].get<std::string>() << ")\n";
  os << "  e = " << num(s["e"]) << "   e_instant = " << num(s["e_instant"]) << "   St = " << num(s["St"])
     << "   Re = " << num(s["Re"]) << "\n";
  if (!s["group_velocity_m_s"].is_null())
    os << "  group velocity = " << num(s["group_velocity_m_s"]) << " m/s (no separation; centre-of-mass velocity at t = "
       << num(s["group_velocity_at_s"]) << " s, when the relative velocity vanished)\n";
  if (!s["min_gap_m"].is_null()) os << "  min gap = " << num(s["min_gap_m"]) << " m, max contact force = " << num(s["max_contact_force_N"]) << " N\n";
  std::string eff;
  for (const auto& x : s["effects"]) eff += (eff.empty() ? "" : ", ") + x.get<std::string>();
  os << "  effects: " << eff << "\n";
  const auto& sol = s["solver"];
  os << "  " << sol["integrator"].get<std::string>() << " rtol " << sol["rtol"].get<double>() << ": "
     << sol["steps"].get<long>() << " steps, " << sol["rhs_evals"].get<long>() << " rhs evals, "
     << sol["root_events"].get<long>() << " events, " << sol["error_test_fails"].get<long>() << " error-test fails; "
     << std::setprecision(3) << s["wall_time_s"].get<double>() * 1e3 << " ms\n";
  const auto& mod = s["model"];
  if (mod.contains("history.kernel")) {
    os << "  history: " << mod["history.kernel"].get<std::string>() << " kernel, " << mod["history.evaluator"].get<std::string>()
       << " evaluator";
    if (mod.contains("history.modes")) os << ", " << mod["history.modes"].get<std::string>() << " modes";
    os << "; peak |f_H| = " << num(s["max_history_force_N"]) << " N; " << sol["linear_solver"].get<std::string>()
       << " linear solver, state size " << sol["state_size"].get<long>() << "\n";
  }
  if (s.contains("flow")) {
    const auto& f = s["flow"];
    os << "  flow: " << f["grid"]["cells_per_diameter"].get<int>() << " cells/D, " << f["grid"]["levels"].get<int>() << " levels, "
       << f["steps"].get<long>() << " flow steps of " << std::setprecision(3) << 1e3 * f["dt_s"].get<double>() << " ms, "
       << f["ms_per_step"].get<double>() << " ms per step, " << f["krylov_iterations_per_step"].get<double>()
       << " GMRES iterations per step; of the wall time " << std::setprecision(2) << 100 * f["flow_share"].get<double>()
       << " % in the flow kernel, " << 100 * f["start_up_time_s"].get<double>() / s["wall_time_s"].get<double>()
       << " % in its start-up (" << f["start_up_steps"].get<long>() << " steps, " << f["start"].get<std::string>() << ")\n";
  }
  for (const auto& w : s["warnings"]) os << "  warning: " << w.get<std::string>() << "\n";
  return os.str();
}

}  // namespace imcol
