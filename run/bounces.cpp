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

/// One object per contact (docs/bounces.md): times, velocities, apex and every named measure of e.
}  // namespace

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
    b["t_separation_s"] = or_null(c.t_out);
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
    b["impact_velocity_m_s"] = or_null(ui);
    b["rebound_velocity_m_s"] = sep ? or_null(ur) : nlohmann::ordered_json(nullptr);
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
    b["apex_gap_m"] = sep ? nlohmann::ordered_json(tr.gap[ia]) : nlohmann::ordered_json(nullptr);  // no flight: no apex
    b["t_apex_s"] = sep ? nlohmann::ordered_json(tr.t[ia]) : nlohmann::ordered_json(nullptr);

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


}  // namespace imcol::run
