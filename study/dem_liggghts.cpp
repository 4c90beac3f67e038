// SPDX-License-Identifier: BSD-3-Clause
#include "study/dem_liggghts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "model/pair.hpp"
#include "study/dem_lookup.hpp"

namespace imcol::study {

std::optional<HookeContact> hooke_contact(const Scene& s, double char_vel) {
  if (s.spheres.empty() || !s.has_target()) return std::nullopt;
  const model::PairGeometry pg(s);  // m*, r*, and Y* = E* (the same definition: global_properties.cpp's Yeff)
  return HookeContact{pg.m_star, pg.a_star, pg.E_star, char_vel};
}

namespace {

/// The points with St (the DEM convention) and e, and the largest impact speed among them (characteristicVelocity).
std::vector<ReplayPoint> replay_points(const std::vector<DemPoint>& pts, bool pair, double& U_max) {
  std::vector<ReplayPoint> out;
  U_max = 0;
  for (const auto& p : pts) {
    const auto St = dem_St(p, pair);
    if (!St || !p.e || !(*St > 0)) continue;
    out.push_back({*St, *p.e, *p.e > 0});
    if (p.impact_speed_m_s) U_max = std::max(U_max, std::abs(*p.impact_speed_m_s));
  }
  std::sort(out.begin(), out.end(), [](const ReplayPoint& a, const ReplayPoint& b) { return a.St < b.St; });
  return out;
}

std::vector<double> all_St(const std::vector<ReplayPoint>& pts) {
  std::vector<double> St;
  for (const auto& p : pts) St.push_back(p.St);
  return St;
}

/// rms and max |e_replay − e| over the points used.
void used_residuals(const std::vector<ReplayPoint>& pts, const std::vector<double>& model, double& rms, double& mx) {
  double ss = 0;
  std::size_t n = 0;
  mx = 0;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (pts[i].used) ss += (model[i] - pts[i].e) * (model[i] - pts[i].e), mx = std::max(mx, std::abs(model[i] - pts[i].e)), ++n;
  rms = n ? std::sqrt(ss / static_cast<double>(n)) : 0;
}

/// The table replayed with a constant e per contact: St at first touch, e looked up (docs/dem.md (a)).
void replay_table(LiggghtsExport& x) {
  std::vector<RestitutionRow> rows;
  for (const auto& p : x.points) rows.push_back({p.St, p.e});
  for (const auto& r : rows) {
    if (!(r.e > 0)) continue;
    const double e = lookup_restitution(rows, r.St);
    const double U = impact_speed_for_stokes(x.contact, x.mu, r.St);
    x.table_max_difference = std::max(x.table_max_difference, std::abs(replay_constant_e(x.contact, e, U, x.step).e - r.e));
    ++x.table_rows;
  }
}

/// e at every point with the fitted rule, Y* and V_c scaled, against the base contact's.
void stiffness_cases(LiggghtsExport& x) {
  const std::vector<double> St = all_St(x.points);
  const std::vector<double> base = replayed_restitution(x.contact, x.fit->rule, St, x.step);
  for (const bool same_dt : {false, true})
    for (const auto& [fy, fv] : {std::pair{0.01, 1.0}, std::pair{100.0, 1.0}, std::pair{1.0, 0.1}, std::pair{1.0, 10.0}}) {
      HookeContact c = x.contact;
      c.Y_eff *= fy, c.char_vel *= fv;
      ReplayStep step = x.step;
      if (same_dt) step.dt = hooke_contact_time(x.contact) / x.step.steps_per_contact;
      StiffnessCase k{fy, fv, same_dt, hooke_contact_time(c) / (step.dt ? *step.dt : hooke_contact_time(c) / step.steps_per_contact)};
      const std::vector<double> e = replayed_restitution(c, x.fit->rule, St, step);
      for (std::size_t i = 0; i < e.size(); ++i) k.max_change = std::max(k.max_change, std::abs(e[i] - base[i]));
      x.stiffness.push_back(k);
    }
}

/// The two fits through the replay (e_max free, and fixed to e_dry) and each point's replayed e.
void fit_rule(LiggghtsExport& x, std::optional<double> e_dry) {
  std::vector<ReplaySample> samples;
  for (const auto& p : x.points)
    if (p.used) samples.push_back({p.St, p.e});
  x.fit = fit_viscous_rule(samples, x.contact, x.mu, std::nullopt, x.step);
  if (e_dry && *e_dry > 0 && *e_dry <= 1) x.fit_fixed = fit_viscous_rule(samples, x.contact, x.mu, e_dry, x.step);
  const std::vector<double> e = replayed_restitution(x.contact, x.fit->rule, all_St(x.points), x.step);
  for (std::size_t i = 0; i < e.size(); ++i) x.points[i].e_fit = e[i];
}

/// The exp formula's parameters put into the rule and replayed.
void replay_formula(LiggghtsExport& x, const DemFit& f) {
  if (f.exp < 0) return;
  const run::RestitutionFit& ex = f.fits[static_cast<std::size_t>(f.exp)];
  if (!(ex.St_c > 0 && ex.e_dry > 0 && ex.e_dry <= 1)) return;
  x.formula = ViscousRule{x.mu, ex.St_c, ex.e_dry};
  const std::vector<double> e = replayed_restitution(x.contact, *x.formula, all_St(x.points), x.step);
  for (std::size_t i = 0; i < e.size(); ++i) x.points[i].e_formula = e[i];
  used_residuals(x.points, e, x.formula_rms, x.formula_max);
}

/// Why the scene or the points allow no fit ("" when they do).
std::string missing_inputs(const Scene& base, const std::optional<HookeContact>& c, const std::vector<ReplayPoint>& pts) {
  if (!base.fluid) return "the scene has no liquid: the viscous rule has no St";
  if (!c) return "the scene has no target or wall: no contact to replay";
  const auto used = static_cast<std::size_t>(std::count_if(pts.begin(), pts.end(), [](const ReplayPoint& p) { return p.used; }));
  if (used < min_replay_samples(true))
    return "a fit through the replay needs at least " + std::to_string(min_replay_samples(true)) + " points with e > 0; there are " +
           std::to_string(used);
  return "";
}

}  // namespace

LiggghtsExport liggghts_export(const Scene& base, const std::vector<DemPoint>& pts, const DemFit& f, std::optional<double> e_dry) {
  LiggghtsExport x;
  double U_max = 0;
  x.points = replay_points(pts, f.pair, U_max);
  x.char_vel_from_points = U_max > 0;
  const std::optional<HookeContact> c = hooke_contact(base, U_max > 0 ? U_max : 1.0);
  x.error = missing_inputs(base, c, x.points);
  if (!x.error.empty()) return x;
  x.contact = *c;
  x.mu = base.fluid->viscosity;
  x.k_n = hooke_k_n(x.contact);
  x.contact_time = hooke_contact_time(x.contact);
  const Solid& j = base.two_spheres() ? static_cast<const Solid&>(base.spheres[1]) : static_cast<const Solid&>(*base.wall);
  x.E_i = base.spheres[0].youngs_modulus, x.nu_i = base.spheres[0].poisson_ratio, x.E_j = j.youngs_modulus, x.nu_j = j.poisson_ratio;
  fit_rule(x, e_dry);
  replay_formula(x, f);
  replay_table(x);
  stiffness_cases(x);
  return x;
}

namespace {

using J = nlohmann::ordered_json;

J contact_json(const LiggghtsExport& x) {
  J j;
  j["youngsModulus_Pa"] = {x.E_i, x.E_j};
  j["poissonsRatio"] = {x.nu_i, x.nu_j};
  j["Y_eff_Pa"] = x.contact.Y_eff;
  j["m_eff_kg"] = x.contact.m_eff;
  j["r_eff_m"] = x.contact.r_eff;
  j["characteristicVelocity_m_s"] = x.contact.char_vel;
  j["characteristicVelocity_is"] = x.char_vel_from_points ? "the largest impact speed of the points" : "1 m/s (no impact speed measured)";
  j["k_n_N_per_m"] = x.k_n;
  j["contact_time_s"] = x.contact_time;
  j["steps_per_contact"] = x.step.steps_per_contact;
  j["dt_s"] = x.contact_time / x.step.steps_per_contact;
  j["limitForce"] = x.step.limit == ForceLimit::on ? "on" : "off";
  j["note"] = "the scene's materials stand for every point: at a fixed number of steps per contact the replay's e depends on St only "
              "(m*, r*, mu and k_n cancel), so a point's own sizes or densities would give the same e";
  return j;
}

J replay_fit_json(const ReplayFit& f) {
  J j;
  j["CriticalStokes"] = f.rule.critical_stokes;
  j["MaximumRestitution"] = f.rule.maximum_restitution;
  j["MaximumRestitution_is"] = f.e_max_free ? "fitted" : "fixed to the scene's e_dry";
  j["rms_residual"] = f.rms_residual;
  j["max_residual"] = f.max_residual;
  j["max_residual_at_St"] = f.max_residual_St;
  j["within_tolerance"] = f.max_residual <= kReplayTolerance;
  j["evaluations"] = f.evaluations;
  return j;
}

J points_json(const LiggghtsExport& x) {
  J a = J::array();
  for (const auto& p : x.points) {
    J r{{"St", p.St}, {"e", p.e}, {"used_in_fit", p.used}, {"e_replay", p.e_fit}, {"residual", p.e_fit - p.e}};
    r["e_replay_exp_formula"] = x.formula ? J(p.e_formula) : J(nullptr);
    a.push_back(r);
  }
  return a;
}

J beyond_json(const LiggghtsExport& x) {
  J a = J::array();
  for (const auto& p : x.points)
    if (p.used && std::abs(p.e_fit - p.e) > kReplayTolerance) a.push_back({{"St", p.St}, {"e", p.e}, {"e_replay", p.e_fit}, {"residual", p.e_fit - p.e}});
  return a;
}

J stiffness_json(const LiggghtsExport& x) {
  J a = J::array();
  for (const auto& k : x.stiffness)
    a.push_back({{"Y_eff_factor", k.Y_factor}, {"characteristicVelocity_factor", k.char_vel_factor},
                 {"step", k.same_dt ? "the base contact's dt" : "the same steps per contact"}, {"steps_per_contact", k.steps_per_contact},
                 {"max_change_in_e", k.max_change}});
  return a;
}

J formula_json(const LiggghtsExport& x) {
  if (!x.formula) return nullptr;
  return J{{"CriticalStokes", x.formula->critical_stokes}, {"MaximumRestitution", x.formula->maximum_restitution},
           {"rms_residual", x.formula_rms}, {"max_residual", x.formula_max}, {"within_tolerance", x.formula_max <= kReplayTolerance},
           {"note", "the exp formula's St_c and e_dry (dem.json `exp`) put into the rule: what LIGGGHTS would do with them"}};
}

}  // namespace

nlohmann::ordered_json liggghts_json(const LiggghtsExport& x) {
  J j;
  j["model"] = "LIGGGHTS(-PUBLIC) pair_style gran model hooke ... viscous on (src/normal_model_hooke.h)";
  j["replay"] = "a 1-D re-implementation of that normal force from its source, velocity Verlet as fix nve/sphere; not a LIGGGHTS run";
  j["rule"] = "at every step of a contact: St = m* v_n / (6 pi mu r*^2) with the signed normal velocity (< 0 approaching), "
              "ln e = ln(MaximumRestitution) + CriticalStokes / St, gamma_n = sqrt(4 m* k_n ln^2 e / (ln^2 e + pi^2))";
  j["fit_method"] = "least squares in e over the points with e > 0: an 11 x 11 grid, then BOBYQA";
  j["fit_error"] = x.error.empty() ? J(nullptr) : J(x.error);
  if (!x.error.empty()) return j;
  j["FluidViscosity"] = x.mu;
  const J fitted = replay_fit_json(*x.fit);
  for (auto it = fitted.begin(); it != fitted.end(); ++it) j[it.key()] = *it;
  j["tolerance_max_residual"] = kReplayTolerance;
  j["beyond_tolerance"] = beyond_json(x);
  const auto used = std::find_if(x.points.begin(), x.points.end(), [](const ReplayPoint& p) { return p.used; });
  j["valid_St"] = {used->St, x.points.back().St};
  j["MaximumRestitution_fixed"] = x.fit_fixed ? replay_fit_json(*x.fit_fixed) : J(nullptr);
  j["exp_formula_replayed"] = formula_json(x);
  j["points"] = points_json(x);
  j["contact"] = contact_json(x);
  j["stiffness"] = stiffness_json(x);
  j["table_replay"] = {{"rule", "docs/dem.md (a): St at first touch, e from dem_table.csv, gamma_n for that e for the whole contact"},
                       {"rows", x.table_rows}, {"max_difference_in_e", x.table_max_difference}};
  return j;
}

std::string liggghts_text(const LiggghtsExport& x) {
  if (!x.error.empty()) return "LIGGGHTS hooke viscous: no fit: " + x.error;
  const ReplayFit& f = *x.fit;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "LIGGGHTS hooke viscous (replayed): CriticalStokes = %.2f, MaximumRestitution = %.3f, residual in e rms %.4f max %.4f at St %.1f%s",
                f.rule.critical_stokes, f.rule.maximum_restitution, f.rms_residual, f.max_residual, f.max_residual_St,
                f.max_residual <= kReplayTolerance ? "" : " (beyond 0.03: the rule does not reach imcol's e there)");
  return buf;
}

}  // namespace imcol::study
