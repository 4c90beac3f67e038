// SPDX-License-Identifier: BSD-3-Clause
#include "run/bounces.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "core/measure.hpp"
#include "run/energy_budget.hpp"

namespace imcol::run {

using model::CollisionModel;

void Track::reserve(std::size_t n, bool energies) {
  for (auto* v : {&t, &gap, &u, &z1, &u1, &z2, &u2}) v->reserve(n);
  if (!energies) return;
  work.reserve(n);
  ke_spheres.reserve(n);
  ke_added.reserve(n);
}

double Track::cross(std::size_t i, double g) const {
  const double w = (g - gap[i - 1]) / (gap[i] - gap[i - 1]);
  return t[i - 1] + w * (t[i] - t[i - 1]);
}

double Track::u_at(std::size_t i, double g) const {
  const double w = (g - gap[i - 1]) / (gap[i] - gap[i - 1]);
  return u[i - 1] + w * (u[i] - u[i - 1]);
}

std::size_t Track::first_at_or_after(double t0) const { return std::lower_bound(t.begin(), t.end(), t0) - t.begin(); }

namespace {

constexpr double kYangHuntWindow = 0.010;  // s: the seed's "10 to 15 ms" fit interval (Yang & Hunt 2006), its lower end
constexpr double kJosephDistance = 0.1;    // units of D: the stretch "just prior to and after impact" (our reading)

/// The gap's rate (−U_rel) beside the track, for the Hermite interpolant of the gap.
std::vector<double> gap_rate(const Track& tr) {
  std::vector<double> r(tr.u.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = -tr.u[i];
  return r;
}

/// U_rel from a least-squares fit of the gap over [t0, t1] (degree 1: the line's slope; degree 2: the parabola's
/// slope at t_ref): the gap closes at U_rel.
std::optional<double> fitted_u(const Track& tr, const std::vector<double>& rate, double t0, double t1, int degree = 1,
                               double t_ref = NAN) {
  if (!(t1 > t0)) return std::nullopt;
  auto f = fit_polynomial_hermite(tr.t, tr.gap, rate, t0, t1, degree, std::isnan(t_ref) ? 0.5 * (t0 + t1) : t_ref);
  if (!f) return std::nullopt;
  return -f->slope;
}

/// e from an impact and a rebound U_rel (< 0 moving apart), and those velocities: negative values are clipped to 0
/// and say why.
void put_e(MeasureResult& m, std::optional<double> u_in, std::optional<double> u_out, const char* why_negative) {
  m.impact_velocity_m_s = u_in;
  m.rebound_velocity_m_s = u_out;
  if (!u_in || !u_out || !(*u_in > 0)) {
    m.e.reset();
    return;
  }
  const double e = -*u_out / *u_in;
  m.e = std::max(0.0, e);
  if (e < 0) {
    m.e_raw = e;
    m.note = why_negative;
  }
}

/// One contact (ContactLog) and the flights around it: the approach [t_from, t_in] and the rebound [t_sep, t_next].
struct Flights {
  const Contact& c;
  double t_from, t_next, t_sep;
  bool sep;      // the contact separated
  bool started;  // the run started inside this contact zone: its impact velocity is the initial one
  bool last;     // the rebound's flight ends with the run (t_next is the run's last sample)
  std::size_t a0, a1, r0, r1;  // samples: approach [a0, a1], rebound [r0, r1] (r1 also bounds the apex search)
};

/// A window of W before the contact and one after the separation, both shortened alike to the flights.
double flight_window(const Flights& f, double W) {
  double Wk = f.started ? W : std::min(W, f.c.t_in - f.t_from);
  if (f.sep) Wk = std::min(Wk, f.t_next - f.t_sep);
  return Wk;
}

/// The time from t0 until U_rel first differs from u0 by more than `fraction` of |u0| (linear between samples), going
/// forward (dir = +1) or backward (dir = −1) no further than t_stop; +inf if it does not.
double speed_change_time(const Track& tr, double t0, double u0, double fraction, int dir, double t_stop) {
  const double du = fraction * std::abs(u0);
  if (dir > 0) {
    for (std::size_t i = tr.first_at_or_after(t0); i < tr.t.size() && tr.t[i] <= t_stop; ++i) {
      if (!(std::abs(tr.u[i] - u0) > du)) continue;
      if (i == 0 || tr.t[i - 1] < t0) return tr.t[i] - t0;
      const double a = std::abs(tr.u[i - 1] - u0), b = std::abs(tr.u[i] - u0);
      return tr.t[i - 1] + (du - a) / (b - a) * (tr.t[i] - tr.t[i - 1]) - t0;
    }
  } else {
    for (std::size_t i = tr.first_at_or_after(t0); i-- > 0 && tr.t[i] >= t_stop;) {
      if (!(std::abs(tr.u[i] - u0) > du)) continue;
      if (i + 1 >= tr.t.size() || tr.t[i + 1] > t0) return t0 - tr.t[i];
      const double a = std::abs(tr.u[i + 1] - u0), b = std::abs(tr.u[i] - u0);
      return t0 - (tr.t[i + 1] - (du - a) / (b - a) * (tr.t[i + 1] - tr.t[i]));
    }
  }
  return INFINITY;
}

/// fit_time (and yang_hunt_2006): least-squares slopes over windows of W before the contact and after the separation.
MeasureResult fit_time_measure(const Track& tr, const std::vector<double>& rate, const Flights& f, double W) {
  MeasureResult ft;
  const double Wk = flight_window(f, W);
  std::optional<double> ui = f.started ? std::optional<double>(f.c.u_in) : fitted_u(tr, rate, f.c.t_in - Wk, f.c.t_in);
  std::optional<double> ur = f.sep ? fitted_u(tr, rate, f.t_sep, f.t_sep + Wk) : std::optional<double>(0.0);
  put_e(ft, ui, ur, "the rebound fit's slope points toward the target: the sphere fell back within the window; e clipped to 0");
  ft.window_s = Wk;
  ft.cut_by_end_of_run = f.sep && f.last && f.t_next - f.t_sep < W * (1 - 1e-9) && Wk == f.t_next - f.t_sep;
  if (!f.sep && ft.e) ft.e = 0.0;
  return ft;
}

/// One fitted parabola of a sphere's position, for drawing: z(t) = z + u (t − t_ref) + ½ a (t − t_ref)².
std::optional<FittedPosition> parabola(const Track& tr, const std::vector<double>& z, const std::vector<double>& u, double t0,
                                       double t1, double t_ref, int degree) {
  const auto p = fit_polynomial_hermite(tr.t, z, u, t0, t1, degree, t_ref);
  if (!p) return std::nullopt;
  return FittedPosition{p->t_ref, p->value, p->slope, p->accel};
}

/// A measure's window [t0, t1] and each sphere's fitted position in it (degree 1: a line, 2: a parabola), for
/// trajectory.png.
FittedStretch fitted_window(const Track& tr, double t0, double t1, double t_ref, int degree, bool pair) {
  FittedStretch s{t0, t1, parabola(tr, tr.z1, tr.u1, t0, t1, t_ref, degree), std::nullopt, pair};
  if (pair) s.z2 = parabola(tr, tr.z2, tr.u2, t0, t1, t_ref, degree);
  return s;
}

/// contact_ends' window: W, or the shortest of the bounds below (both windows alike), and what bounded it (empty: W).
/// A parabola describes the flight only while U_rel changes little: each window ends before U_rel has changed by more
/// than speed_change of its value at the contact's end (under a constant deceleration, that fraction of the time to
/// the apex or from the start of the fall).
std::pair<double, std::string> ends_window(const Track& tr, const Flights& f, double W, double speed_change) {
  double Wk = W;
  std::string by;
  auto bound = [&](double w, const char* why) {
    if (w < Wk) {
      Wk = w;
      by = why;
    }
  };
  if (!f.started) {
    bound(f.c.t_in - f.t_from, "approach flight");
    bound(speed_change_time(tr, f.c.t_in, f.c.u_in, speed_change, -1, f.t_from), "approach speed change");
  }
  if (f.sep) {
    bound(f.t_next - f.t_sep, f.last ? "end of run" : "rebound flight");
    if (f.c.u_out) bound(speed_change_time(tr, f.t_sep, *f.c.u_out, speed_change, +1, f.t_next), "rebound speed change");
  }
  return {Wk, by};
}

/// contact_ends (the model's own e): parabolas
/// z = z0 + U t + ½ a t² fitted by least squares to the gap over a window before the contact and after the separation, the velocities being their slopes at the contact's ends (the inward
/// δ_SS crossing, the separation). The window is the time to travel `distance` (m) at the impact speed (U_rel at the
/// inward δ_SS crossing), shortened alike to the flights and to where U_rel has changed by `speed_change` of its value
/// at either end. A steady force (gravity, drag nearly) is a constant acceleration: the parabola takes it up instead of
/// tilting the velocity. A dry collision gives e = e_d exactly. The end slopes are compared with U_rel at the δ_SS
/// crossings (`end_mismatch`, in units of the impact speed); above `tolerance` the entry carries a `warning`.
MeasureResult contact_ends_measure(const Track& tr, const std::vector<double>& rate, const Flights& f, double distance,
                                   double speed_change, double tolerance, bool pair) {
  MeasureResult ce;
  if (!(f.c.u_in > 0)) {
    put_e(ce, std::nullopt, std::nullopt, "");
    ce.missing = "no approach at the contact (U_rel <= 0 at the inward delta_ss crossing)";
    return ce;
  }
  const double W = distance / f.c.u_in;
  const auto [Wk, by] = ends_window(tr, f, W, speed_change);
  const double a0 = f.c.t_in - Wk, r1 = f.t_sep + Wk;
  std::optional<double> ui = f.started ? std::optional<double>(f.c.u_in) : fitted_u(tr, rate, a0, f.c.t_in, 2, f.c.t_in);
  std::optional<double> ur = f.sep ? fitted_u(tr, rate, f.t_sep, r1, 2, f.t_sep) : std::optional<double>(0.0);
  put_e(ce, ui, ur, "the rebound parabola's slope at the separation points toward the target; e clipped to 0");
  if (!f.sep && ce.e) ce.e = 0.0;
  ce.distance_m = distance;
  ce.window_s = Wk;
  if (!by.empty()) {
    ce.shortened_from_s = W;
    ce.shortened_by = by;
  }
  ce.cut_by_end_of_run = by == "end of run";
  // The end slopes against U_rel at the δ_SS crossings (the model's exact values), in units of the impact speed.
  std::optional<double> mis_in, mis_out;
  if (ui && !f.started) mis_in = std::abs(*ui - f.c.u_in) / f.c.u_in;
  if (ur && f.sep && f.c.u_out) mis_out = std::abs(*ur - *f.c.u_out) / f.c.u_in;
  ce.end_mismatch = EndMismatch{mis_in, mis_out};
  const bool bad_in = mis_in && *mis_in > tolerance, bad_out = mis_out && *mis_out > tolerance;
  if (bad_in || bad_out) {
    std::ostringstream os;
    os << std::setprecision(3) << "the " << (bad_out ? "rebound" : "approach") << " parabola's slope at the "
       << (bad_out ? "separation" : "contact") << " differs from U_rel at the delta_ss crossing by " << (bad_out ? *mis_out : *mis_in)
       << " of the impact speed (more than measure.ends_tolerance = " << tolerance << "): U_rel changes fast there";
    if (!by.empty()) os << " (window " << 1e3 * Wk << " ms, shortened from " << 1e3 * W << " ms by the " << by << ")";
    os << ", so a parabola over a trajectory's stretch misses it";
    ce.warning = os.str();
  }
  // The windows and each sphere's fitted position in them (for trajectory.png).
  ce.stretches = true;
  if (!f.started) ce.approach = fitted_window(tr, a0, f.c.t_in, f.c.t_in, 2, pair);
  if (f.sep) ce.rebound = fitted_window(tr, f.t_sep, r1, f.t_sep, 2, pair);
  if (!ui && !f.started) ce.missing = "the approach window is not covered by the run";
  else if (f.sep && !ur) ce.missing = "the rebound window is not covered by the run";
  return ce;
}

/// e_instant: the U_rel at the inward crossing of instant_gap and at the next outward one.
std::optional<double> instant_e(const std::vector<Crossing>& inst, const Flights& f) {
  std::optional<double> ii, io;
  for (const auto& x : inst) {
    if (x.in && x.t >= f.t_from && x.t <= f.t_sep) ii = x.u;
    if (!x.in && ii && !io && x.t >= f.c.t_in && x.t <= f.t_next) io = x.u;
  }
  if (ii && io) return std::max(0.0, -*io / *ii);
  return ii && !f.sep ? std::optional<double>(0.0) : std::nullopt;
}

/// The apex: the largest gap between this contact and the next one (or the end); none without a flight.
void put_apex(const Track& tr, const Flights& f, Bounce& b) {
  std::size_t ia = tr.first_at_or_after(f.c.t_in);
  for (std::size_t i = ia; i <= f.r1; ++i)
    if (tr.gap[i] > tr.gap[ia]) ia = i;
  if (!f.sep) return;
  b.apex_gap_m = tr.gap[ia];
  b.t_apex_s = tr.t[ia];
}

/// The largest gap among samples i0..i1.
std::size_t highest(const Track& tr, std::size_t i0, std::size_t i1) {
  std::size_t ia = i0;
  for (std::size_t i = i0; i <= i1 && i < tr.t.size(); ++i)
    if (tr.gap[i] > tr.gap[ia]) ia = i;
  return ia;
}

/// Half a flight's excursion above the gap g0 where it is shorter than d, else d: the approach's fall from the largest
/// gap of its flight (`approach`), or the rebound's rise to its apex once the apex is known (the flight ends before the
/// run does, or the run ended with the rebound stalled: U_rel above −stall_speed). A camera sees all of a short
/// excursion; its first half keeps 71 % of the speed under a constant deceleration.
double camera_distance(const Track& tr, const Flights& f, double g0, double d, double stall_speed, bool approach) {
  double x = INFINITY;
  if (approach && !f.started && f.a1 > f.a0) x = tr.gap[highest(tr, f.a0, f.a1)] - g0;
  if (!approach && f.sep) {
    const std::size_t ia = highest(tr, f.r0, f.r1);
    const bool at_end = f.last && ia + 1 >= tr.t.size();
    if (!at_end || tr.u.back() > -stall_speed) x = tr.gap[ia] - g0;
  }
  return x > 0 && x < d ? 0.5 * x : d;
}

/// fit_distance (and joseph_2001): slopes from the last inward crossing of delta_ss + d to the contact, and from the
/// separation to the first outward crossing; each side over half its flight's excursion where that is shorter
/// (camera_distance).
MeasureResult fit_distance_measure(const Track& tr, const std::vector<double>& rate, const Flights& f, double g0, double d,
                                   double stall_speed, bool pair) {
  MeasureResult fd;
  const double d_in = camera_distance(tr, f, g0, d, stall_speed, true), d_out = camera_distance(tr, f, g0, d, stall_speed, false);
  const double g_in = g0 + d_in, g_out = g0 + d_out;
  std::optional<double> fd_in, fd_out, ta, tb;
  for (std::size_t i = std::max<std::size_t>(f.a0, 1); i <= f.a1 && i < tr.t.size(); ++i)
    if (tr.gap[i - 1] >= g_in && tr.gap[i] < g_in) ta = tr.cross(i, g_in);
  if (f.started) fd_in = f.c.u_in;
  else if (ta) fd_in = fitted_u(tr, rate, *ta, f.c.t_in);
  if (f.sep)
    for (std::size_t i = std::max<std::size_t>(f.r0, 1); i <= f.r1 && !tb; ++i)
      if (tr.gap[i - 1] < g_out && tr.gap[i] >= g_out) tb = tr.cross(i, g_out);
  if (f.sep && tb) fd_out = fitted_u(tr, rate, f.t_sep, *tb);
  else if (!f.sep) fd_out = 0.0;
  put_e(fd, fd_in, fd_out, "the fitted rebound moves toward the target; e clipped to 0");
  fd.distance_m = d;
  if (d_in < d) fd.approach_distance_m = d_in;
  if (d_out < d) fd.rebound_distance_m = d_out;
  // The stretches and each sphere's fitted line in them (for trajectory.png).
  fd.stretches = true;
  if (ta) fd.approach = fitted_window(tr, *ta, f.c.t_in, 0.5 * (*ta + f.c.t_in), 1, pair);
  if (tb) fd.rebound = fitted_window(tr, f.t_sep, *tb, 0.5 * (f.t_sep + *tb), 1, pair);
  if (!fd_in && !f.started) fd.missing = "the approach did not start beyond delta_ss + fit_distance";
  else if (f.sep && !tb) fd.missing = "the rebound did not reach delta_ss + fit_distance (the run ended before its apex)";
  return fd;
}

/// at_gap: U_rel where the gap last crossed g_at inward before the separation and first crossed it outward after
/// the contact (`initial_gap`: a start inside the contact zone below g_at takes the initial velocity).
MeasureResult at_gap_measure(const Track& tr, const Flights& f, double g_at, double initial_gap) {
  MeasureResult ag;
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
  ag.gap_m = g_at;
  if (!ag_in) ag.missing = "the approach did not cross at_gap inward";
  else if (f.sep && !ag_out) ag.missing = "the rebound did not reach at_gap (apex below it, or the run ended)";
  return ag;
}

/// peak_rebound: the largest rebound speed over the rebound's flight / the largest approach speed over the approach's.
MeasureResult peak_rebound_measure(const Track& tr, const Flights& f) {
  MeasureResult pr;
  double u_max_in = f.started ? f.c.u_in : 0.0, u_max_out = 0.0;
  for (std::size_t i = f.a0; i <= f.a1 && i < tr.t.size(); ++i) u_max_in = std::max(u_max_in, tr.u[i]);
  if (f.sep)
    for (std::size_t i = f.r0; i <= f.r1; ++i) u_max_out = std::max(u_max_out, -tr.u[i]);
  put_e(pr, u_max_in > 0 ? std::optional<double>(u_max_in) : std::nullopt, -u_max_out, "");
  pr.impact_speed_m_s = u_max_in;
  pr.rebound_speed_m_s = u_max_out;
  return pr;
}

MeasureResult with_reference(MeasureResult m, const char* reference) {
  m.reference = reference;
  return m;
}

/// Every named measure of one contact (docs/bounces.md), in summary.json's order.
std::vector<std::pair<EMeasure, MeasureResult>> named_measures(const CollisionModel& model, const Scene& sc, const Track& tr,
                                                               const std::vector<double>& rate, const Flights& f,
                                                               const std::vector<Crossing>& inst) {
  const double D = 2 * model.radius(0);
  const double stall_speed = 2 * sc.measure.stall_fraction * std::abs(f.c.u_in);  // a rebound this slow has stalled
  const bool pair = model.n_spheres() == 2;
  MeasureResult instant;
  instant.velocities = false;
  instant.e = instant_e(inst, f);
  instant.gap_m = sc.measure.instant_gap * D;
  return {
      {EMeasure::contact_ends, contact_ends_measure(tr, rate, f, sc.measure.ends_distance * D, sc.measure.ends_speed_change,
                                                    sc.measure.ends_tolerance, pair)},
      {EMeasure::yang_hunt_2006, with_reference(fit_time_measure(tr, rate, f, kYangHuntWindow),
                                                "Yang & Hunt, Phys. Fluids 18, 121506 (2006); seed eq. 6.1: lines over 10 ms")},
      {EMeasure::joseph_2001,
       with_reference(fit_distance_measure(tr, rate, f, model.delta_ss_m(), kJosephDistance * D, stall_speed, pair),
                      "Joseph, Zenit, Hunt & Rosenwinkel, J. Fluid Mech. 433 (2001): lines over the last/first 0.1 D (our reading)")},
      {EMeasure::gondret_2002, with_reference(peak_rebound_measure(tr, f), "Gondret, Lance & Petit, Phys. Fluids 14, 643 (2002): peak "
                                                                           "speeds of the position signal (our reading)")},
      {EMeasure::fit_time, fit_time_measure(tr, rate, f, sc.measure.window)},
      {EMeasure::fit_distance, fit_distance_measure(tr, rate, f, model.delta_ss_m(), sc.measure.fit_distance * D, stall_speed, pair)},
      {EMeasure::at_gap, at_gap_measure(tr, f, sc.measure.at_gap * D, model.initial_gap())},
      {EMeasure::peak_rebound, peak_rebound_measure(tr, f)},
      {EMeasure::instant, instant}};
}

/// The flights around contact k of cs (the run's last sample at t_final).
Flights flights(const CollisionModel& model, const Track& tr, const std::vector<Contact>& cs, std::size_t k, double t_final) {
  const Contact& c = cs[k];
  const double t_from = k == 0 ? 0.0 : cs[k - 1].t_out.value_or(cs[k - 1].t_in);  // this approach's flight begins
  const double t_next = k + 1 < cs.size() ? cs[k + 1].t_in : t_final;               // the rebound's flight ends
  const double t_sep = c.t_out.value_or(t_next);
  return Flights{c, t_from, t_next, t_sep, c.t_out.has_value(), model.started_in_contact() && k == 0, k + 1 == cs.size(),
                 tr.first_at_or_after(t_from), tr.first_at_or_after(c.t_in), tr.first_at_or_after(t_sep),
                 std::min(tr.first_at_or_after(t_next), tr.t.size() - 1)};
}

/// The distinct measures whose e differs from the bounce's e by more than measure.disagreement (a pair identical by
/// construction once, under both names).
void put_disagreement(const Scene& sc, Bounce& b) {
  if (!b.e) return;
  for (const auto& [name, m] : b.e_measures) {
    const std::string label = measure_label(sc, name);
    if (!label.empty() && m.e && std::abs(*m.e - *b.e) > sc.measure.disagreement) b.measures_disagree.push_back({label, *m.e});
  }
}

/// One contact: its times, the named measures, e by measure.e, the apex, the energy budget and the disagreement.
Bounce measure_bounce(const CollisionModel& model, const Scene& sc, const Track& tr, const std::vector<double>& rate, const Flights& f,
                      const std::vector<Crossing>& inst, int number) {
  Bounce b;
  b.contact = number;
  b.t_contact_s = f.c.t_in;
  b.t_separation_s = f.c.t_out;
  b.impact_speed_at_delta_ss_m_s = f.c.u_in;
  b.e_measures = named_measures(model, sc, tr, rate, f, inst);
  const MeasureResult& m = *b.measure(sc.measure.e);
  b.e = m.e;
  b.e_is = sc.measure.e;
  b.impact_velocity_m_s = m.impact_velocity_m_s;
  if (f.sep) b.rebound_velocity_m_s = m.rebound_velocity_m_s;
  b.e_instant = b.measure(EMeasure::instant)->e;
  put_apex(tr, f, b);
  b.energy_budget = energy_budget(tr, {f.t_from, f.c.t_in, f.c.t_out, f.t_next});
  put_disagreement(sc, b);
  return b;
}

/// The warnings on the measure e is: contact_ends' slopes that miss U_rel at δ_SS, fits clipped to 0.
void warn_on_measures(const Scene& sc, const std::vector<Bounce>& out, std::vector<std::string>& warnings) {
  std::vector<int> clipped, ends_warned;
  for (const auto& b : out) {
    const MeasureResult& m = *b.measure(sc.measure.e);
    if (m.e_raw) clipped.push_back(b.contact);  // a clipped fit is a warning where it is e; elsewhere its e_raw and note say it
    if (sc.measure.e == EMeasure::contact_ends && m.warning) ends_warned.push_back(b.contact);
  }
  if (!ends_warned.empty()) {
    std::ostringstream os;
    os << "e (contact_ends) at contact " << ends_warned[0] << ": " << *out[ends_warned[0] - 1].measure(EMeasure::contact_ends)->warning;
    for (std::size_t i = 1; i < ends_warned.size(); ++i) os << (i == 1 ? "; also at contact " : ", ") << ends_warned[i];
    warnings.push_back(os.str());
  }
  if (!clipped.empty()) {
    std::ostringstream os;
    os << "at contact";
    for (std::size_t i = 0; i < clipped.size(); ++i) os << (i ? ", " : " ") << clipped[i];
    os << " the rebound fit of e (" << to_string(sc.measure.e) << ") points toward the target (the sphere fell back within its window): "
          "e is clipped to 0 (e_raw in its e_measures entry)";
    warnings.push_back(os.str());
  }
}

}  // namespace

std::string measure_label(const Scene& sc, EMeasure m) {
  // Pairs identical by construction: the generic measure first, the paper's procedure second.
  const struct {
    EMeasure generic, paper;
    bool same;
  } pairs[] = {{EMeasure::fit_time, EMeasure::yang_hunt_2006, sc.measure.window == kYangHuntWindow},
               {EMeasure::fit_distance, EMeasure::joseph_2001, sc.measure.fit_distance == kJosephDistance},
               {EMeasure::peak_rebound, EMeasure::gondret_2002, true}};
  for (const auto& p : pairs) {
    if (!p.same) continue;
    if (m == p.generic) return std::string(to_string(p.generic)) + "/" + to_string(p.paper);
    if (m == p.paper) return "";
  }
  return to_string(m);
}

std::vector<Bounce> measure_bounces(const CollisionModel& model, const Watch& watch, const Scene& sc, const Track& tr,
                                    std::vector<std::string>& warnings) {
  const std::vector<Contact>& cs = watch.contacts.contacts();
  const double t_final = tr.t.empty() ? 0.0 : tr.t.back();
  const std::vector<double> rate = gap_rate(tr);
  std::vector<Bounce> out;
  for (std::size_t k = 0; k < cs.size(); ++k)
    out.push_back(measure_bounce(model, sc, tr, rate, flights(model, tr, cs, k, t_final), watch.instant.crossings(), static_cast<int>(k + 1)));
  warn_on_measures(sc, out, warnings);
  return out;
}

}  // namespace imcol::run
