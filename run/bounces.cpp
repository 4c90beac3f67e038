#include "run/bounces.hpp"

#include <algorithm>
#include <optional>

#include "core/measure.hpp"
#include "run/json_util.hpp"

namespace imcol::run {

using contact::CollisionModel;

double Track::cross(std::size_t i, double g) const {
  const double w = (g - gap[i - 1]) / (gap[i] - gap[i - 1]);
  return t[i - 1] + w * (t[i] - t[i - 1]);
}

double Track::u_at(std::size_t i, double g) const {
  const double w = (g - gap[i - 1]) / (gap[i] - gap[i - 1]);
  return u[i - 1] + w * (u[i] - u[i - 1]);
}

std::size_t Track::first_at_or_after(double t0) const { return std::lower_bound(t.begin(), t.end(), t0) - t.begin(); }

Track track_from_rows(const std::vector<std::vector<double>>& rows, std::size_t u_rel_column) {
  Track tr;
  for (const auto& r : rows) {
    tr.t.push_back(r[0]);
    tr.gap.push_back(r[3]);
    tr.u.push_back(r[u_rel_column]);
  }
  return tr;
}

namespace {

/// U_rel from the least-squares slope of the gap over [t0, t1] (the gap closes at U_rel).
std::optional<double> fitted_u(const Track& tr, double t0, double t1) {
  if (!(t1 > t0)) return std::nullopt;
  auto f = fit_line_continuous(tr.t, tr.gap, t0, t1);
  if (!f) return std::nullopt;
  return -f->slope;
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

/// One contact and the flights around it: the approach [t_from, t_in] and the rebound [t_sep, t_next].
struct Contact {
  double t_in, u_in;
  std::optional<double> t_out;
};
struct Flights {
  const Contact& c;
  double t_from, t_next, t_sep;
  bool sep;      // the contact separated
  bool started;  // the run started inside this contact zone: its impact velocity is the initial one
  std::size_t a0, a1, r0, r1;  // samples: approach [a0, a1], rebound [r0, r1] (r1 also bounds the apex search)
};

/// fit_time: least-squares slopes over windows of W before the contact and after the separation, both shortened
/// alike to the flights. Also sets the contact's impact and rebound velocities.
nlohmann::ordered_json fit_time_measure(const Track& tr, const Flights& f, double W, nlohmann::ordered_json& b) {
  nlohmann::ordered_json ft;
  double Wk = std::min(W, f.c.t_in - f.t_from);
  if (f.sep) Wk = std::min(Wk, f.t_next - f.t_sep);
  std::optional<double> ui = f.started ? std::optional<double>(f.c.u_in) : fitted_u(tr, f.c.t_in - Wk, f.c.t_in);
  std::optional<double> ur = f.sep ? fitted_u(tr, f.t_sep, f.t_sep + Wk) : std::optional<double>(0.0);
  put_e(ft, ui, ur, "the rebound fit's slope points toward the target: the sphere fell back within the window; e clipped to 0");
  ft["window_s"] = Wk;
  if (!f.sep && ft["e"].is_number()) ft["e"] = 0.0;
  b["impact_velocity_m_s"] = or_null(ui);
  b["rebound_velocity_m_s"] = f.sep ? or_null(ur) : nlohmann::ordered_json(nullptr);
  return ft;
}

struct Crossing {
  double t, u;
  bool in;
};

/// e_instant: the U_rel at the inward crossing of instant_gap and at the next outward one.
nlohmann::ordered_json instant_e(const std::vector<Crossing>& inst, const Flights& f) {
  std::optional<double> ii, io;
  for (const auto& x : inst) {
    if (x.in && x.t >= f.t_from && x.t <= f.t_sep) ii = x.u;
    if (!x.in && ii && !io && x.t >= f.c.t_in && x.t <= f.t_next) io = x.u;
  }
  if (ii && io) return std::max(0.0, -*io / *ii);
  return ii && !f.sep ? nlohmann::ordered_json(0.0) : nlohmann::ordered_json(nullptr);
}

/// The apex: the largest gap between this contact and the next one (or the end); none without a flight.
void put_apex(const Track& tr, const Flights& f, nlohmann::ordered_json& b) {
  std::size_t ia = tr.first_at_or_after(f.c.t_in);
  for (std::size_t i = ia; i <= f.r1; ++i)
    if (tr.gap[i] > tr.gap[ia]) ia = i;
  b["apex_gap_m"] = f.sep ? nlohmann::ordered_json(tr.gap[ia]) : nlohmann::ordered_json(nullptr);
  b["t_apex_s"] = f.sep ? nlohmann::ordered_json(tr.t[ia]) : nlohmann::ordered_json(nullptr);
}

/// fit_distance: slopes from the last inward crossing of g_fd = delta_ss + d to the contact, and from the
/// separation to the first outward crossing.
nlohmann::ordered_json fit_distance_measure(const Track& tr, const Flights& f, double g_fd, double d_fit) {
  nlohmann::ordered_json fd;
  std::optional<double> fd_in, fd_out, ta, tb;
  for (std::size_t i = std::max<std::size_t>(f.a0, 1); i <= f.a1 && i < tr.t.size(); ++i)
    if (tr.gap[i - 1] >= g_fd && tr.gap[i] < g_fd) ta = tr.cross(i, g_fd);
  if (f.started) fd_in = f.c.u_in;
  else if (ta) fd_in = fitted_u(tr, *ta, f.c.t_in);
  if (f.sep)
    for (std::size_t i = std::max<std::size_t>(f.r0, 1); i <= f.r1 && !tb; ++i)
      if (tr.gap[i - 1] < g_fd && tr.gap[i] >= g_fd) tb = tr.cross(i, g_fd);
  if (f.sep && tb) fd_out = fitted_u(tr, f.t_sep, *tb);
  else if (!f.sep) fd_out = 0.0;
  put_e(fd, fd_in, fd_out, "the fitted rebound moves toward the target; e clipped to 0");
  fd["distance_m"] = d_fit;
  if (!fd_in && !f.started) fd["missing"] = "the approach did not start beyond delta_ss + fit_distance";
  else if (f.sep && !tb) fd["missing"] = "the rebound did not reach delta_ss + fit_distance (apex below it, or the run ended)";
  return fd;
}

/// at_gap: U_rel where the gap last crossed g_at inward before the separation and first crossed it outward after
/// the contact (`initial_gap`: a start inside the contact zone below g_at takes the initial velocity).
nlohmann::ordered_json at_gap_measure(const Track& tr, const Flights& f, double g_at, double initial_gap) {
  nlohmann::ordered_json ag;
  std::optional<double> ag_in, ag_out;
  const std::size_t s1 = std::min(tr.first_at_or_after(f.t_sep), tr.t.size() - 1);
  for (std::size_t i = std::max<std::size_t>(f.a0, 1); i <= s1; ++i)
    if (tr.gap[i - 1] >= g_at && tr.gap[i] < g_at) ag_in = tr.u_at(i, g_at);
  if (f.started && !ag_in && initial_gap <= g_at) ag_in = f.c.u_in;
  if (f.sep) {
    for (std::size_t i = std::max<std::size_t>(f.a1, 1); i <= f.r1 && !ag_out; ++i)
      if (tr.gap[i - 1] < g_at && tr.gap[i] >= g_at) ag_out = tr.u_at(i, g_at);
  } else {
    ag_out = 0.0;
  }
  put_e(ag, ag_in, ag_out, "");
  ag["gap_m"] = g_at;
  if (!ag_in) ag["missing"] = "the approach did not cross at_gap inward";
  else if (f.sep && !ag_out) ag["missing"] = "the rebound did not reach at_gap (apex below it, or the run ended)";
  return ag;
}

/// peak_rebound: the largest rebound speed over the rebound's flight / the largest approach speed over the approach's.
nlohmann::ordered_json peak_rebound_measure(const Track& tr, const Flights& f) {
  nlohmann::ordered_json pr;
  double u_max_in = f.started ? f.c.u_in : 0.0, u_max_out = 0.0;
  for (std::size_t i = f.a0; i <= f.a1 && i < tr.t.size(); ++i) u_max_in = std::max(u_max_in, tr.u[i]);
  if (f.sep)
    for (std::size_t i = f.r0; i <= f.r1; ++i) u_max_out = std::max(u_max_out, -tr.u[i]);
  put_e(pr, u_max_in > 0 ? std::optional<double>(u_max_in) : std::nullopt, -u_max_out, "");
  pr["impact_speed_m_s"] = u_max_in;
  pr["rebound_speed_m_s"] = u_max_out;
  return pr;
}

}  // namespace

nlohmann::ordered_json measure_bounces(const CollisionModel& model, const Scene& sc, const Track& tr, std::vector<std::string>& warnings) {
  std::vector<Contact> cs;
  std::vector<Crossing> inst;
  for (const auto& ev : model.events()) {
    if (ev.name == "gap=delta_ss (in)" || ev.name == "start inside the contact zone") cs.push_back({ev.t, ev.u_rel, std::nullopt});
    else if (ev.name == "gap=delta_ss (out)" && !cs.empty() && !cs.back().t_out) cs.back().t_out = ev.t;
    else if (ev.name == "gap=instant_gap (in)") inst.push_back({ev.t, ev.u_rel, true});
    else if (ev.name == "gap=instant_gap (out)") inst.push_back({ev.t, ev.u_rel, false});
  }
  if (model.started_in_contact() && !cs.empty()) cs.front().u_in = model.initial_u_rel();
  const double D = 2 * model.radius(0);
  const double d_fit = sc.measure.fit_distance * D, g_at = sc.measure.at_gap * D, g_fd = model.delta_ss_m() + d_fit;
  const double t_final = tr.t.empty() ? 0.0 : tr.t.back();
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  bool any_clipped = false;
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const Contact& c = cs[k];
    const double t_from = k == 0 ? 0.0 : cs[k - 1].t_out.value_or(cs[k - 1].t_in);  // this approach's flight begins
    const double t_next = k + 1 < cs.size() ? cs[k + 1].t_in : t_final;               // the rebound's flight ends
    const double t_sep = c.t_out.value_or(t_next);
    const Flights f{c, t_from, t_next, t_sep, c.t_out.has_value(), model.started_in_contact() && k == 0,
                    tr.first_at_or_after(t_from), tr.first_at_or_after(c.t_in), tr.first_at_or_after(t_sep),
                    std::min(tr.first_at_or_after(t_next), tr.t.size() - 1)};
    nlohmann::ordered_json b;
    b["contact"] = k + 1;
    b["t_contact_s"] = c.t_in;
    b["t_separation_s"] = or_null(c.t_out);
    b["impact_speed_at_delta_ss_m_s"] = c.u_in;
    const nlohmann::ordered_json ft = fit_time_measure(tr, f, sc.measure.window, b);
    if (ft.contains("e_raw")) any_clipped = true;
    b["e"] = ft["e"];
    b["e_instant"] = instant_e(inst, f);
    put_apex(tr, f, b);
    b["e_measures"] = {{"fit_time", ft},
                       {"fit_distance", fit_distance_measure(tr, f, g_fd, d_fit)},
                       {"at_gap", at_gap_measure(tr, f, g_at, model.initial_gap())},
                       {"peak_rebound", peak_rebound_measure(tr, f)},
                       {"instant", {{"e", b["e_instant"]}, {"gap_m", sc.measure.instant_gap * D}}}};
    out.push_back(b);
  }
  if (any_clipped)
    warnings.push_back("a rebound fit over measure.window points toward the target (the sphere fell back within the window): "
                       "that contact's e is clipped to 0 (e_raw in its e_measures.fit_time)");
  return out;
}

}  // namespace imcol::run
