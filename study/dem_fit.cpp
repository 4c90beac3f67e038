// SPDX-License-Identifier: BSD-3-Clause
#include "study/dem_fit.hpp"

#include <algorithm>
#include <cmath>

namespace imcol::study {

using run::RestitutionFit;
using run::RestitutionForm;

const char* const kDemStConvention =
    "m* U / (6 pi mu a*^2): m*, a* the reduced mass and radius (a wall: the sphere's m, a), U the impact speed";

std::vector<DemPoint> dem_points(const SweepResult& sweep) {
  std::vector<DemPoint> out;
  for (const auto& p : sweep.points) {
    DemPoint d;
    d.value = p.value;
    d.ok = p.ok;
    if (p.ok) {
      const auto& s = p.summary;
      d.e_status = e_status(s);
      if (s.U_i1 && s.U_i2) d.impact_speed_m_s = *s.U_i1 - *s.U_i2;
      d.St = s.St;
      d.St_B_eq_6_2 = s.St_B_eq_6_2;
      d.e = s.e;
    }
    out.push_back(d);
  }
  return out;
}

std::optional<double> dem_St(const DemPoint& p, bool pair) { return pair ? p.St_B_eq_6_2 : p.St; }

namespace {

/// The samples the fits take (the points with a St); a point with e but no St (no liquid: St is infinite) is
/// counted apart, not as one without e.
std::vector<run::RestitutionSample> dem_samples(const std::vector<DemPoint>& pts, DemFit& f) {
  std::vector<run::RestitutionSample> samples;
  for (const auto& p : pts) {
    const auto St = dem_St(p, f.pair);
    if (!St && p.e) ++f.without_St;
    else samples.push_back({St.value_or(NAN), St ? p.e : std::nullopt});
  }
  double St_no_rebound_max = 0;
  for (const auto& s : samples) {
    if (!s.e) ++f.without_e;
    else if (*s.e > 0) ++f.used;
    else ++f.no_rebound, St_no_rebound_max = std::max(St_no_rebound_max, s.St);
  }
  if (f.no_rebound) f.St_no_rebound_max = St_no_rebound_max;
  return samples;
}

/// The best fit and the exponential one (DemFit::best, DemFit::exp).
void choose_fits(DemFit& f) {
  for (std::size_t k = 0; k < f.fits.size(); ++k) {
    const RestitutionFit& x = f.fits[k];
    const RestitutionFit* best = f.best < 0 ? nullptr : &f.fits[static_cast<std::size_t>(f.best)];
    if (x.e_dry <= 1 && (!best || (x.e_dry_free && !best->e_dry_free) || (x.e_dry_free == best->e_dry_free && x.rms_residual < best->rms_residual)))
      f.best = static_cast<int>(k);
    if (x.form == RestitutionForm::exponential && (f.exp < 0 || (x.e_dry_free && x.e_dry <= 1))) f.exp = static_cast<int>(k);
  }
}

}  // namespace

DemFit fit_dem(const std::vector<DemPoint>& pts, std::optional<double> e_dry, bool liquid, bool pair) {
  DemFit f;
  f.pair = pair;
  f.total = pts.size();
  const std::vector<run::RestitutionSample> samples = dem_samples(pts, f);
  // Both forms, e_dry fixed to the scene's (when it has one) and free; a fit without enough points is left out and said.
  std::vector<std::optional<double>> e_drys;
  if (e_dry) e_drys.push_back(e_dry);
  e_drys.push_back(std::nullopt);
  if (!liquid) f.fit_error = "the scene has no liquid: St is infinite and e does not depend on it (a DEM code takes e_dry as it is)";
  for (const auto form : {RestitutionForm::exponential, RestitutionForm::linear})
    for (const auto& d : e_drys) {
      if (!liquid) break;
      try {
        f.fits.push_back(run::fit_restitution(samples, form, d));
      } catch (const std::exception& e) {  // too few points (or no convergence): said in dem.json and on the terminal
        if (f.fit_error.empty()) f.fit_error = e.what();
      }
    }
  choose_fits(f);
  return f;
}

nlohmann::ordered_json dem_fit_json(const RestitutionFit& f, bool pair) {
  nlohmann::ordered_json j;
  j["form"] = to_string(f.form);
  j["formula"] = formula(f.form);
  j["e_dry_is"] = f.e_dry_free ? "fitted" : "fixed to the scene's";
  j["St_c"] = f.St_c;
  j["St_c_std_error"] = f.St_c_std_error;
  if (pair) j["St_c_in_St_B_table_6_1"] = f.St_c / 2;  // the same fit against the summary's St (half the DEM St)
  j["e_dry"] = f.e_dry;
  if (f.e_dry_free) j["e_dry_std_error"] = f.e_dry_std_error;
  j["rms_residual"] = f.rms_residual;
  j["max_residual"] = f.max_residual;
  j["fits_within_tolerance"] = f.max_residual <= kDemFitTolerance;
  j["points_used"] = f.used;
  j["valid_St"] = {f.St_min, f.St_max};
  j["iterations"] = f.iterations;
  if (f.e_dry > 1) j["note"] = "e_dry > 1 is no restitution: the form needs more than it to reach the points; take the fit with e_dry fixed";
  return j;
}

namespace {

double or_nan(const std::optional<double>& v) { return v.value_or(NAN); }

}  // namespace

Table dem_table(const std::vector<DemPoint>& pts, const std::string& column, std::optional<double> e_dry, bool pair) {
  Table t;
  t.rows = pts.size();
  auto& point = t.add("point");
  auto& value = t.add(column);
  auto& speed = t.add("impact_speed_m_s");
  auto& St = t.add("St");
  TableColumn* St_pair = pair ? &t.add("St_B_eq_6_2") : nullptr;
  auto& e = t.add("e");
  auto& ratio = t.add("e_over_e_dry");
  auto& status = t.add("status", true);
  auto& st = t.add("e_status", true);
  auto& used = t.add("used_in_fit");
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto& p = pts[i];
    point.numbers.push_back(static_cast<double>(i));
    value.numbers.push_back(p.value);
    speed.numbers.push_back(or_nan(p.impact_speed_m_s));
    St.numbers.push_back(or_nan(p.St));
    if (St_pair) St_pair->numbers.push_back(or_nan(p.St_B_eq_6_2));
    e.numbers.push_back(or_nan(p.e));
    ratio.numbers.push_back(p.e && e_dry ? *p.e / *e_dry : NAN);
    status.text.push_back(p.ok ? "ok" : "failed");
    st.text.push_back(p.e_status);
    used.numbers.push_back(p.e && *p.e > 0 && dem_St(p, pair) ? 1 : 0);
  }
  return t;
}

}  // namespace imcol::study
