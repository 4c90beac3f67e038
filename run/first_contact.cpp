// SPDX-License-Identifier: BSD-3-Clause
#include "run/first_contact.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <tuple>

#include "core/measure.hpp"

namespace imcol::run {

using model::CollisionModel;

namespace {

/// Least-squares line of a sphere's position over [t0, t1] (Hermite interpolant of the track).
std::optional<LineFit> line(const Track& tr, const std::vector<double>& z, const std::vector<double>& u, double t0, double t1) {
  auto f = fit_polynomial_hermite(tr.t, z, u, t0, t1, 1, 0.0);
  if (!f) return std::nullopt;
  return LineFit{f->slope, f->value};
}

/// Why e is undefined for a run that never collided (no contact and no stopped approach) or has no target.
void no_collision(const CollisionModel& model, const Scene& sc, bool collided, FirstContact& m, std::vector<std::string>& warnings) {
  // A longer solver.t_end would change e only if an approach is under way or gravity can start one.
  const bool can_approach = model.initial_u_rel() > 0 || sc.has(Effect::gravity);
  m.t_end_too_short = model.has_target() && !collided && can_approach;
  if (model.has_target() && !collided) {
    m.e_missing = can_approach ? "no collision by t_end: the gap never reached delta_ss and the approach never stopped; e is undefined"
                               : "no collision: the spheres are not approaching (U_rel(0) <= 0, no gravity), so no t_end gives one; e is undefined";
    warnings.push_back(*m.e_missing);
  }
  if (!model.has_target()) {
    // A free sphere (no wall, no second sphere): a settling or rising motion, not a collision; said once, like every null e.
    m.e_missing = "a free sphere: no wall or second sphere, so no collision and no e (the trajectory is the result)";
    warnings.push_back(*m.e_missing);
  }
}

/// The impact and rebound lines (fit_time): windows of measure.window before t_ref (the first δ_SS crossing, or the
/// closest approach) and after the separation (or the run's last window), shortened alike to a short approach and to
/// the next contact.
void fit_lines(const CollisionModel& model, const Watch& watch, const Scene& sc, const Track& tr, double t_ref, FirstContact& m,
               std::vector<std::string>& warnings) {
  const bool pair = model.n_spheres() == 2;
  const double W = sc.measure.window;
  const double t_final = tr.t.empty() ? 0.0 : tr.t.back();
  // A short approach shortens both windows alike, so that they stay symmetric in time.
  const bool in_contact = model.started_in_contact();
  double Wfit = in_contact ? W : std::min(W, t_ref);
  // All bounces: the rebound window ends at the next contact at the latest (both shortened alike).
  const auto& contacts = watch.contacts.contacts();
  if (m.separated && contacts.size() > 1) Wfit = std::min(Wfit, contacts[1].t_in - *model.t_separation());
  if (in_contact) {
    // No approach to fit: the impact velocities are the initial ones.
    m.u_i1 = sc.spheres[0].velocity;
    m.u_i2 = pair ? sc.spheres[1].velocity : 0.0;
    std::ostringstream os;
    os << "started inside the contact zone: the zone is shortened to the initial gap (" << model.delta_ss_m()
       << " m) and the impact velocities are the initial ones";
    warnings.push_back(os.str());
  } else {
    if (Wfit < W) warnings.push_back("the approach lasted less than the fit window: both fits use windows of the approach's length");
    auto f1 = line(tr, tr.z1, tr.u1, t_ref - Wfit, t_ref);
    auto f2 = pair ? line(tr, tr.z2, tr.u2, t_ref - Wfit, t_ref) : std::optional<LineFit>(LineFit{});
    if (f1 && f2) {
      m.u_i1 = f1->slope;
      m.u_i2 = f2->slope;
    }
  }
  // Rebound window: from the separation, or the last window of the run.
  const double t_post = m.separated ? *model.t_separation() : std::max(t_ref, t_final - Wfit);
  auto g1 = line(tr, tr.z1, tr.u1, t_post, t_post + Wfit);
  auto g2 = pair ? line(tr, tr.z2, tr.u2, t_post, t_post + Wfit) : std::optional<LineFit>(LineFit{});
  m.fit_window = Wfit;
  if (g1 && g2) {
    m.u_r1 = g1->slope;
    m.u_r2 = g2->slope;
  }
}

/// A pair that never separated: its centre-of-mass velocity where the two move together (the rebound lines agree).
void group_velocity(const CollisionModel& model, const Watch& watch, const Track& tr, FirstContact& m, std::vector<std::string>& warnings) {
  const double closing = *m.u_r1 - *m.u_r2;  // > 0: still approaching over the last window
  const double m1 = model.mass(0), m2 = model.mass(1);
  const double ug = (m1 * *m.u_r1 + m2 * *m.u_r2) / (m1 + m2);
  if (std::abs(closing) <= 0.1 * std::abs(ug)) {
    // U_G at a stated moment, not at t_end (the pair keeps slowing down under drag): the centre-of-mass
    // velocity when the relative velocity first vanished (the loading -> unloading switch after contact,
    // or the stopped approach without contact), where the two spheres move together.
    m.t_group = watch.contacts.t_together();
    if (!m.t_group) m.t_group = watch.stalled_approach.t_closest();
    if (m.t_group) {
      for (std::size_t i = 0; i < tr.t.size(); ++i)
        if (tr.t[i] == *m.t_group) {
          m.group_velocity = (m1 * tr.u1[i] + m2 * tr.u2[i]) / (m1 + m2);
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

/// e from the fitted lines: the restitution after a separation (clipped at 0), else 0 (and a pair's group velocity).
void e_from_lines(const CollisionModel& model, const Watch& watch, const Track& tr, FirstContact& m, std::vector<std::string>& warnings) {
  if (m.separated) {
    m.e = restitution(*m.u_i1, *m.u_i2, *m.u_r1, *m.u_r2);
    if (*m.e < 0) {
      m.e_fit_raw = m.e;
      m.e = 0.0;
      std::ostringstream os;
      os << "fit_time e = " << *m.e_fit_raw << ": the rebound line's slope points toward the target (the sphere fell back "
         << "within measure.window); clipped to 0; contact_ends, at_gap and peak_rebound do not have this defect";
      warnings.push_back(os.str());
    }
    return;
  }
  m.e = 0.0;  // never separated
  const double closing = *m.u_r1 - *m.u_r2;  // > 0: still approaching over the last window
  if (model.n_spheres() == 2) group_velocity(model, watch, tr, m, warnings);
  if (model.t_contact() && -closing > 1e-3 * std::abs(*m.u_i1 - *m.u_i2)) {
    m.t_end_too_short = true;
    std::ostringstream os;
    os << "no separation by t_end, but the gap was growing at " << -closing
       << " m/s over the last window (e = 0 by definition; a longer solver.t_end may show a rebound)";
    warnings.push_back(os.str());
  }
}

/// St and Re at impact, and e_instant (U_rel at the instant gap's crossings).
void impact_numbers(const CollisionModel& model, const Watch& watch, const Scene& sc, FirstContact& m, std::vector<std::string>& warnings) {
  if (m.u_i1 && sc.fluid) {
    const double u_rel = *m.u_i1 - *m.u_i2;
    std::tie(m.St, m.St_62) = stokes_numbers(model, sc, u_rel);
    m.Re = sc.fluid->density * 2 * model.radius(0) * u_rel / sc.fluid->viscosity;
    if (!model.t_contact())
      warnings.push_back("no contact: St and Re use the approach velocity fitted over measure.window before the closest approach, "
                         "where the liquid had already slowed the pair (St_initial is the nominal value)");
  }
  if (const auto u_in = watch.instant.u_in()) {
    if (const auto u_out = watch.instant.u_out()) m.e_instant = -*u_out / *u_in;
    else if (!m.separated) m.e_instant = 0.0;
  }
  if (!m.e_instant && model.t_contact())
    warnings.push_back("e_instant: the gap did not cross measure.instant_gap inward and outward before t_end");
}

}  // namespace

std::pair<double, double> stokes_numbers(const CollisionModel& model, const Scene& sc, double u_rel) {
  const double st62 = stokes_number(model.m_star(), u_rel, sc.fluid->viscosity, model.a_star());
  return {model.n_spheres() == 2 ? st62 / 2 : st62, st62};
}

FirstContact measure_first_contact(const CollisionModel& model, const Watch& watch, const Scene& sc, const Track& tr,
                                   std::vector<std::string>& warnings) {
  const double t_final = tr.t.empty() ? 0.0 : tr.t.back();
  const std::optional<double> t_at_rest = watch.rest.since();
  FirstContact m;
  m.fit_window = sc.measure.window;
  m.separated = model.t_separation().has_value();
  const std::optional<double> t_closest = watch.stalled_approach.t_closest();
  const bool collided = model.t_contact() || t_closest;  // reached contact or a closest approach
  no_collision(model, sc, collided, m, warnings);
  if (model.has_target() && collided) {
    // Approach window ends at the first δ_SS crossing, or at the closest approach without contact.
    fit_lines(model, watch, sc, tr, model.t_contact().value_or(*t_closest), m, warnings);
    if (m.u_i1 && m.u_r1) e_from_lines(model, watch, tr, m, warnings);
    if (m.u_i1 && !m.u_r1 && !m.separated) {
      if (t_at_rest) {
        m.e = 0.0;  // at rest on the target: no t_end changes e = 0
      } else {
        m.t_end_too_short = true;
        m.e_missing = "the run ended less than measure.window after the " + std::string(model.t_contact() ? "contact" : "closest approach") +
                      ", without a separation: no rebound fit, so e is undefined (raise solver.t_end)";
        warnings.push_back(*m.e_missing);
      }
    }
    impact_numbers(model, watch, sc, m, warnings);
  }
  // A run that ended at rest is complete: a longer t_end cannot change anything.
  if (t_at_rest) m.t_end_too_short = false;
  m.stopped_by_t_end = !t_at_rest && t_final >= sc.solver.t_end * (1 - 1e-12);
  return m;
}

std::string e_by_measure_line(const Scene& sc, const Bounce& b) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(3);
  double lo = INFINITY, hi = -INFINITY;
  std::string rest;
  // e's measure may share its label with a generic one ("fit_distance/joseph_2001"), listed under the generic name.
  const std::string e_name = to_string(b.e_is);
  std::string e_label = measure_label(sc, b.e_is);
  for (const auto& [k, v] : b.e_measures)
    if (e_label.empty() && measure_label(sc, k).ends_with("/" + e_name)) e_label = measure_label(sc, k);
  for (const auto& [k, v] : b.e_measures) {
    const std::string label = measure_label(sc, k);
    if (label.empty() || !v.e) continue;
    const double e = *v.e;
    lo = std::min(lo, e);
    hi = std::max(hi, e);
    std::ostringstream one;
    one << std::fixed << std::setprecision(3) << label << " " << e;
    if (label == e_label) os << one.str() << " (e)";
    else rest += ", " + one.str();
  }
  os << rest << "; spread " << (hi >= lo ? hi - lo : 0.0) << " (docs/bounces.md)";
  return os.str();
}

void choose_e(const Scene& sc, const std::vector<Bounce>& bounces, FirstContact& m, std::vector<std::string>& warnings) {
  // Without a contact, or before a separation, e is the approach's verdict: 0 when the pair stopped or moves on
  // together (at rest, group motion), null when a longer run could still show a rebound.
  if (bounces.empty() || !bounces[0].t_separation_s) return;
  const Bounce& b = bounces[0];
  const char* name = to_string(sc.measure.e);
  const MeasureResult& em = *b.measure(sc.measure.e);
  m.e_fit_raw = em.e_raw;
  if (em.e) {
    m.e = em.e;
    m.e_missing.reset();
  } else {
    m.e.reset();
    if (!m.e_missing) m.e_missing = std::string(name) + ": " + em.missing.value_or("the measure could not be taken");
    warnings.push_back("e is undefined: " + *m.e_missing);
  }
  // t_end too short: judged by the measure e is, when the run stopped at t_end (not at rest, not by measure.bounces):
  // its rebound window was cut by the run's end, or it could not be taken.
  if (m.stopped_by_t_end && (em.cut_by_end_of_run.value_or(false) || (!m.e && bounces.size() == 1))) {
    m.t_end_too_short = true;
    warnings.push_back(m.e ? "t_end cut the " + std::string(name) + " rebound window short"
                           : "t_end ended the run before " + std::string(name) + " could measure the rebound");
  }
  if (m.e) m.e_by_measure = e_by_measure_line(sc, b);
}

void check_plausibility(const CollisionModel& model, const Scene& sc, const FirstContact& m, std::vector<std::string>& warnings) {
  const auto& e = m.e;
  const bool pair = model.n_spheres() == 2;
  if (e && sc.has(Effect::elastic) && *e > model.e_dry() * (1 + 1e-9)) {
    // More elastic than the solids alone: energy was created. Known for the seed's per-sphere added mass with unequal spheres.
    std::ostringstream os;
    const bool hertz_added_mass = !sc.has(Effect::flow) && sc.contact.law == ContactLawKind::hertz && sc.has(Effect::added_mass);
    os << "e = " << *e << " exceeds the dry restitution e_dry = " << model.e_dry() << (hertz_added_mass ? ": " : ": energy was created, ");
    if (sc.has(Effect::flow))  // coupled: e follows the grid far more than rtol (docs/coupling.md "Divergence")
      os << "by the flow coupling's grid (flow.cells_per_diameter = " << sc.flow.cells_per_diameter << ", flow.levels = " << sc.flow.levels
         << ") and blend (contact.delta_sl = " << sc.contact.delta_sl << "), not by solver.rtol: compare grids with `imcol work-precision "
         << sc.path << "`, or refine the grid";
    else if (hertz_added_mass)
      os << "the Hertz law's damping is fitted so that the dry pair (reduced mass m*) returns e_dry, but the immersed spheres also "
            "move the liquid's added mass (" << std::setprecision(2) << 100 * model.implicit_added_mass(model.delta_ss_m()).m11 / model.mass(0)
         << " % of sphere 1's mass at contact), and more inertia on the same dashpot is a more elastic contact; no energy is created "
            "(energy_budget: the contact's loss closes with the kinetic energy)";
    else
      os << "by integration error (tighten solver.rtol, now " << sc.solver.rtol << ")";
    if (pair && sc.has(Effect::added_mass) && sc.added_mass.model == AddedMassModel::seed)
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
}

}  // namespace imcol::run
