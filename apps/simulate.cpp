#include "apps/simulate.hpp"

#include <algorithm>
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

/// The samples one contact's measures read: time, gap and U_rel (> 0 approaching).
struct Track {
  std::vector<double> t, gap, u;
  /// Time where the gap crosses g between samples i−1 and i (linear).
  double cross(std::size_t i, double g) const {
    const double w = (g - gap[i - 1]) / (gap[i] - gap[i - 1]);
    return t[i - 1] + w * (t[i] - t[i - 1]);
  }
  double u_at(std::size_t i, double g) const {
    const double w = (g - gap[i - 1]) / (gap[i] - gap[i - 1]);
    return u[i - 1] + w * (u[i] - u[i - 1]);
  }
  std::size_t first_at_or_after(double t0) const { return std::lower_bound(t.begin(), t.end(), t0) - t.begin(); }
};

/// U_rel from the least-squares slope of the gap over [t0, t1] (the gap closes at U_rel).
std::optional<double> fitted_u(const Track& tr, double t0, double t1) {
  if (!(t1 > t0)) return std::nullopt;
  auto f = fit_line_continuous(tr.t, tr.gap, t0, t1);
  if (!f) return std::nullopt;
  return -f->slope;
}

nlohmann::ordered_json null_or(const std::optional<double>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

/// e from an impact and a rebound U_rel (< 0 moving apart): negative values are clipped to 0 and say why.
void put_e(nlohmann::ordered_json& j, std::optional<double> u_in, std::optional<double> u_out, const char* why_negative) {
  if (!u_in || !u_out || !(*u_in > 0)) {
    j["e"] = nullptr;
    return;
  }
  const double e = -*u_out / *u_in;
  j["e"] = std::max(0.0, e);
  if (e < 0) {
    j["e_raw"] = e;
    j["note"] = why_negative;
  }
}

/// One object per contact (docs/bounces.md): times, velocities, apex and every named measure of e.
nlohmann::ordered_json measure_bounces(const CollisionModel& model, const Scene& sc, const Track& tr, std::vector<std::string>& warnings) {
  struct Contact {
    double t_in, u_in;
    std::optional<double> t_out;
  };
  std::vector<Contact> cs;
  struct Crossing {
    double t, u;
    bool in;
  };
  std::vector<Crossing> inst;
  for (const auto& ev : model.events()) {
    if (ev.name == "gap=delta_ss (in)" || ev.name == "start inside the contact zone") cs.push_back({ev.t, ev.u_rel, std::nullopt});
    else if (ev.name == "gap=delta_ss (out)" && !cs.empty() && !cs.back().t_out) cs.back().t_out = ev.t;
    else if (ev.name == "gap=instant_gap (in)") inst.push_back({ev.t, ev.u_rel, true});
    else if (ev.name == "gap=instant_gap (out)") inst.push_back({ev.t, ev.u_rel, false});
  }
  if (model.started_in_contact() && !cs.empty()) cs.front().u_in = model.initial_u_rel();
  const double D = 2 * model.radius(0), W = sc.measure.window;
  const double d_fit = sc.measure.fit_distance * D, g_at = sc.measure.at_gap * D, g_ss = model.delta_ss_m();
  const double t_final = tr.t.empty() ? 0.0 : tr.t.back();
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  bool any_clipped = false;
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const Contact& c = cs[k];
    const double t_from = k == 0 ? 0.0 : cs[k - 1].t_out.value_or(cs[k - 1].t_in);  // this approach's flight begins
    const double t_next = k + 1 < cs.size() ? cs[k + 1].t_in : t_final;               // the rebound's flight ends
    const bool sep = c.t_out.has_value();
    const double t_sep = c.t_out.value_or(t_next);
    // Samples of the approach flight [t_from, t_in] and of the rebound flight [t_sep, t_next].
    const std::size_t a0 = tr.first_at_or_after(t_from), a1 = tr.first_at_or_after(c.t_in);
    const std::size_t r0 = tr.first_at_or_after(t_sep), r1 = std::min(tr.first_at_or_after(t_next), tr.t.size() - 1);
    const std::size_t c1 = std::min(tr.first_at_or_after(t_next), tr.t.size() - 1);
    nlohmann::ordered_json b;
    b["contact"] = k + 1;
    b["t_contact_s"] = c.t_in;
    b["t_separation_s"] = null_or(c.t_out);
    b["impact_speed_at_delta_ss_m_s"] = c.u_in;

    // fit_time: windows of W before the contact and after the separation, both shortened alike to the flights.
    nlohmann::ordered_json ft;
    double Wk = std::min(W, c.t_in - t_from);
    if (sep) Wk = std::min(Wk, t_next - t_sep);
    const bool started = model.started_in_contact() && k == 0;
    std::optional<double> ui = started ? std::optional<double>(c.u_in) : fitted_u(tr, c.t_in - Wk, c.t_in);
    std::optional<double> ur = sep ? fitted_u(tr, t_sep, t_sep + Wk) : std::optional<double>(0.0);
    put_e(ft, ui, ur, "the rebound fit's slope points toward the target: the sphere fell back within the window; e clipped to 0");
    ft["window_s"] = Wk;
    if (!sep && ft["e"].is_number()) ft["e"] = 0.0;
    if (ft.contains("e_raw")) any_clipped = true;
    b["impact_velocity_m_s"] = null_or(ui);
    b["rebound_velocity_m_s"] = sep ? null_or(ur) : nlohmann::ordered_json(nullptr);
    b["e"] = ft["e"];

    // e_instant: the U_rel at the inward crossing of instant_gap and at the next outward one.
    std::optional<double> ii, io;
    for (const auto& x : inst) {
      if (x.in && x.t >= t_from && x.t <= t_sep) ii = x.u;
      if (!x.in && ii && !io && x.t >= c.t_in && x.t <= t_next) io = x.u;
    }
    if (ii && io) b["e_instant"] = std::max(0.0, -*io / *ii);
    else b["e_instant"] = ii && !sep ? nlohmann::ordered_json(0.0) : nlohmann::ordered_json(nullptr);

    // Apex: the largest gap between this contact and the next one (or the end).
    std::size_t ia = tr.first_at_or_after(c.t_in);
    for (std::size_t i = ia; i <= c1; ++i)
      if (tr.gap[i] > tr.gap[ia]) ia = i;
    b["apex_gap_m"] = tr.gap[ia];
    b["t_apex_s"] = tr.t[ia];

    // fit_distance: from the last inward crossing of delta_ss + d to the contact, and from the separation to the first outward one.
    nlohmann::ordered_json fd;
    const double g_fd = g_ss + d_fit;
    std::optional<double> fd_in, fd_out;
    std::optional<double> ta;
    for (std::size_t i = std::max<std::size_t>(a0, 1); i <= a1 && i < tr.t.size(); ++i)
      if (tr.gap[i - 1] >= g_fd && tr.gap[i] < g_fd) ta = tr.cross(i, g_fd);
    if (started) fd_in = c.u_in;
    else if (ta) fd_in = fitted_u(tr, *ta, c.t_in);
    std::optional<double> tb;
    if (sep)
      for (std::size_t i = std::max<std::size_t>(r0, 1); i <= r1 && !tb; ++i)
        if (tr.gap[i - 1] < g_fd && tr.gap[i] >= g_fd) tb = tr.cross(i, g_fd);
    if (sep && tb) fd_out = fitted_u(tr, t_sep, *tb);
    else if (!sep) fd_out = 0.0;
    put_e(fd, fd_in, fd_out, "the fitted rebound moves toward the target; e clipped to 0");
    fd["distance_m"] = d_fit;
    if (!fd_in && !started) fd["missing"] = "the approach did not start beyond delta_ss + fit_distance";
    else if (sep && !tb) fd["missing"] = "the rebound did not reach delta_ss + fit_distance (apex below it, or the run ended)";

    // at_gap: U_rel where the gap last crossed g inward before the separation and first crossed it outward after the contact.
    nlohmann::ordered_json ag;
    std::optional<double> ag_in, ag_out;
    const std::size_t s1 = std::min(tr.first_at_or_after(t_sep), tr.t.size() - 1);
    for (std::size_t i = std::max<std::size_t>(a0, 1); i <= s1; ++i)
      if (tr.gap[i - 1] >= g_at && tr.gap[i] < g_at) ag_in = tr.u_at(i, g_at);
    if (started && !ag_in && model.initial_gap() <= g_at) ag_in = c.u_in;
    if (sep) {
      for (std::size_t i = std::max<std::size_t>(a1, 1); i <= r1 && !ag_out; ++i)
        if (tr.gap[i - 1] < g_at && tr.gap[i] >= g_at) ag_out = tr.u_at(i, g_at);
    } else {
      ag_out = 0.0;
    }
    put_e(ag, ag_in, ag_out, "");
    ag["gap_m"] = g_at;
    if (!ag_in) ag["missing"] = "the approach did not cross at_gap inward";
    else if (sep && !ag_out) ag["missing"] = "the rebound did not reach at_gap (apex below it, or the run ended)";

    // peak_rebound: the largest rebound speed over the rebound's flight / the largest approach speed over the approach's flight.
    nlohmann::ordered_json pr;
    double u_max_in = started ? c.u_in : 0.0, u_max_out = 0.0;
    for (std::size_t i = a0; i <= a1 && i < tr.t.size(); ++i) u_max_in = std::max(u_max_in, tr.u[i]);
    if (sep)
      for (std::size_t i = r0; i <= r1; ++i) u_max_out = std::max(u_max_out, -tr.u[i]);
    put_e(pr, u_max_in > 0 ? std::optional<double>(u_max_in) : std::nullopt, -u_max_out, "");
    pr["impact_speed_m_s"] = u_max_in;
    pr["rebound_speed_m_s"] = u_max_out;

    b["e_measures"] = {{"fit_time", ft}, {"fit_distance", fd}, {"at_gap", ag}, {"peak_rebound", pr},
                       {"instant", {{"e", b["e_instant"]}, {"gap_m", sc.measure.instant_gap * D}}}};
    out.push_back(b);
  }
  if (any_clipped)
    warnings.push_back("a rebound fit over measure.window points toward the target (the sphere fell back within the window): "
                       "that contact's e is clipped to 0 (e_raw in its e_measures.fit_time)");
  return out;
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

  std::optional<double> e_fit_raw;
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
    double Wfit = in_contact ? W : std::min(W, t_ref);
    // All bounces: the rebound window ends at the next contact at the latest (both shortened alike).
    if (separated) {
      int n_in = 0;
      for (const auto& x : model.events())
        if (x.name == "gap=delta_ss (in)" && ++n_in == (in_contact ? 1 : 2)) {
          Wfit = std::min(Wfit, x.t - *model.t_separation());
          break;
        }
    }
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
      if (separated) {
        e = restitution(*u_i1, *u_i2, *u_r1, *u_r2);
        if (*e < 0) {
          e_fit_raw = e;
          e = 0.0;
          std::ostringstream os;
          os << "e = " << *e_fit_raw << " from the fits: the rebound fit's slope points toward the target (the sphere fell back "
             << "within measure.window); e is clipped to 0 (e_fit_raw); e_measures.at_gap and peak_rebound do not have this defect";
          warnings.push_back(os.str());
        }
      } else {
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
  // Every contact (docs/bounces.md), from the gap and U_rel samples (events included).
  nlohmann::ordered_json bounces = nlohmann::ordered_json::array();
  if (model.has_target() && sc.has(Effect::elastic)) {
    Track tr;
    const std::size_t iu = pair ? 6 : 4;
    for (const auto& r : res.rows) {
      tr.t.push_back(r[0]);
      tr.gap.push_back(r[3]);
      tr.u.push_back(r[iu]);
    }
    if (!tr.t.empty()) bounces = measure_bounces(model, sc, tr, warnings);
  }
  s["e"] = or_null(e);
  s["e_is"] = "fit_time (velocities fitted over measure.window before the first contact and after its separation)";
  if (e_fit_raw) s["e_fit_raw"] = *e_fit_raw;
  s["e_instant"] = or_null(e_inst);
  s["e_instant_gap_m"] = sc.measure.instant_gap * 2 * model.radius(0);
  // The named measures of the first contact (each contact's are in `bounces`).
  if (!bounces.empty()) {
    auto m = bounces[0]["e_measures"];
    m["fit_time"]["e"] = or_null(e);  // as `e` (symmetric windows, also for pairs)
    m["fit_time"]["window_s"] = fit_window;
    s["e_measures"] = m;
  } else {
    s["e_measures"] = nullptr;
  }
  s["bounces_mode"] = sc.measure.bounces;
  s["bounces"] = bounces;
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
  if (s.contains("bounces_mode") && s["bounces_mode"] == "all" && !s["bounces"].empty()) {
    os << "  bounces: contact   t_contact (s)   impact (m/s)   e       apex gap (mm)   t_apex (s)\n";
    for (const auto& b : s["bounces"])
      os << "           " << std::setw(7) << b["contact"].get<int>() << "   " << std::setw(13) << num(b["t_contact_s"], 5) << "   "
         << std::setw(12) << num(b["impact_velocity_m_s"]) << "   " << std::setw(5) << num(b["e"], 3) << "   " << std::setw(13)
         << (b["apex_gap_m"].is_null() ? "n/a" : num(nlohmann::ordered_json(1e3 * b["apex_gap_m"].get<double>()))) << "   "
         << num(b["t_apex_s"], 5) << "\n";
  }
  for (const auto& w : s["warnings"]) os << "  warning: " << w.get<std::string>() << "\n";
  return os.str();
}

}  // namespace imcol
