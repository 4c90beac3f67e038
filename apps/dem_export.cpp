// SPDX-License-Identifier: BSD-3-Clause
#include "apps/dem_export.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "apps/format.hpp"
#include "core/report.hpp"
#include "run/restitution_fit.hpp"

namespace imcol {

namespace fs = std::filesystem;
using run::RestitutionFit;
using run::RestitutionForm;

namespace {

const char* kStConvention = "m* U / (6 pi mu a*^2): m*, a* the reduced mass and radius (a wall: the sphere's m, a), U the impact speed";

/// The St a DEM code computes (kStConvention): the summary's St for a wall, St_B_eq_6_2 for a pair.
std::optional<double> dem_St(const DemPoint& p, bool pair) { return pair ? p.St_B_eq_6_2 : p.St; }

std::string num(double v) { return csv_number(v); }

std::string solid_text(const Solid& s) {
  std::string t = s.material.empty() ? "inline properties" : s.material;
  if (s.density > 0) t += ", density " + num(s.density) + " kg/m3";
  return t;
}

/// The comment lines above dem.csv's header: where the numbers come from, and their units.
std::string csv_comment(const Scene& base, const DemSweep& sw, bool pair) {
  std::ostringstream os;
  os << "# imcol sweep --export dem: e against St, one row per sweep point (docs/dem.md)\n";
  os << "# scene: " << base.name << " (" << sw.scene_file << "), " << (pair ? "sphere-sphere" : "sphere-wall") << ", varied: " << sw.vary
     << " (column " << sw.column << ")\n";
  if (base.fluid)
    os << "# fluid: density " << num(base.fluid->density) << " kg/m3, viscosity " << num(base.fluid->viscosity) << " Pa s"
       << (sw.vary == "viscosity" ? " (the scene's; each row's is in its viscosity column)" : "") << "\n";
  for (std::size_t k = 0; k < base.spheres.size(); ++k)
    os << "# sphere " << k << (k == 0 ? " (impactor)" : " (target)") << ": " << solid_text(base.spheres[k]) << ", diameter "
       << num(base.spheres[k].diameter) << " m, initial velocity "
       << (k == 0 && sw.vary == "velocity" ? "varied (column " + sw.column + ")" : num(base.spheres[k].velocity) + " m/s")
       << (sw.vary == "diameter" || sw.vary == "density" ? " (the scene's; scaled per row, ratios kept)" : "") << "\n";
  if (base.wall) os << "# wall: " << solid_text(*base.wall) << "\n";
  os << "# e_dry = " << (sw.e_dry ? num(*sw.e_dry) : std::string("n/a")) << " (dry restitution of the contact)\n";
  if (pair)
    os << "# St = St_B_table_6_1 (imcol's pair convention, half of eq. 6.2); St_B_eq_6_2 = " << kStConvention << " (the DEM convention)\n";
  else
    os << "# St = " << kStConvention << " (the DEM convention)\n";
  os << "# units: " << sw.column << " SI; impact_speed_m_s m/s (approach speed at contact, from the fitted approach line); St, e, "
        "e_over_e_dry dimensionless; status ok | failed; e_status measured | measures_disagree | not_measured; used_in_fit 1 if e > 0\n";
  return os.str();
}

std::string opt_cell(const std::optional<double>& v) { return v ? csv_number(*v) : std::string(); }

std::string dem_csv(const Scene& base, const DemSweep& sw, const std::vector<DemPoint>& pts, bool pair) {
  std::string out = csv_comment(base, sw, pair);
  out += "point," + sw.column + ",impact_speed_m_s,St," + (pair ? "St_B_eq_6_2," : "") + "e,e_over_e_dry,status,e_status,used_in_fit\n";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto& p = pts[i];
    const std::optional<double> ratio = p.e && sw.e_dry ? std::optional<double>(*p.e / *sw.e_dry) : std::nullopt;
    out += std::to_string(i) + "," + num(p.value) + "," + opt_cell(p.impact_speed_m_s) + "," + opt_cell(p.St) + "," +
           (pair ? opt_cell(p.St_B_eq_6_2) + "," : "") + opt_cell(p.e) + "," + opt_cell(ratio) + "," + (p.ok ? "ok" : "failed") + "," +
           p.e_status + "," + (p.e && *p.e > 0 && dem_St(p, pair) ? "1" : "0") + "\n";
  }
  return out;
}

/// St, e, e/e_dry of every point with both, sorted by St (e = 0 rows included: no rebound there).
std::string lookup_csv(const DemSweep& sw, const std::vector<DemPoint>& pts, bool pair) {
  std::vector<std::pair<double, double>> rows;
  for (const auto& p : pts)
    if (const auto St = dem_St(p, pair); St && p.e) rows.emplace_back(*St, *p.e);
  std::sort(rows.begin(), rows.end());
  std::string out = "St,e,e_over_e_dry\n";
  for (const auto& [St, e] : rows) out += num(St) + "," + num(e) + "," + (sw.e_dry ? num(e / *sw.e_dry) : std::string()) + "\n";
  return out;
}

nlohmann::ordered_json fit_json(const RestitutionFit& f, bool pair) {
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

std::string fit_text(const RestitutionFit& f) {
  std::ostringstream os;
  os << formula(f.form) << ": St_c = " << fixed(f.St_c, 2) << ", e_dry = " << fixed(f.e_dry, 3) << (f.e_dry_free ? "" : " (fixed)")
     << ", residual in e rms " << fixed(f.rms_residual, 4) << " max " << fixed(f.max_residual, 4)
     << (f.max_residual <= kDemFitTolerance ? "" : " (beyond " + fixed(kDemFitTolerance, 2) + ": the form does not fit)");
  return os.str();
}

}  // namespace

std::string export_dem(const fs::path& dir, const Scene& base, const DemSweep& sw, const std::vector<DemPoint>& pts) {
  const bool pair = base.spheres.size() == 2;
  write_file_atomic(dir / "dem.csv", dem_csv(base, sw, pts, pair));
  write_file_atomic(dir / "dem_table.csv", lookup_csv(sw, pts, pair));

  // The fits take the points with a St; a point with e but no St (a scene without a liquid: St is infinite) is
  // counted apart, not as one without e.
  std::vector<run::RestitutionSample> samples;
  std::size_t without_St = 0;
  for (const auto& p : pts) {
    const auto St = dem_St(p, pair);
    if (!St && p.e) ++without_St;
    else samples.push_back({St.value_or(NAN), St ? p.e : std::nullopt});
  }
  // Both forms, e_dry fixed to the scene's (when it has one) and free; a fit without enough points is left out and said.
  std::vector<RestitutionFit> fits;
  std::string fit_error;
  std::vector<std::optional<double>> e_drys;
  if (sw.e_dry) e_drys.push_back(sw.e_dry);
  e_drys.push_back(std::nullopt);
  if (!base.fluid) fit_error = "the scene has no liquid: St is infinite and e does not depend on it (a DEM code takes e_dry as it is)";
  for (const auto form : {RestitutionForm::exponential, RestitutionForm::linear})
    for (const auto& e_dry : e_drys) {
      if (!base.fluid) break;
      try {
        fits.push_back(run::fit_restitution(samples, form, e_dry));
      } catch (const std::exception& e) {  // too few points (or no convergence): said in dem.json and on the terminal
        if (fit_error.empty()) fit_error = e.what();
      }
    }

  nlohmann::ordered_json j;
  j["scene"] = base.name;
  j["scene_file"] = sw.scene_file;
  j["configuration"] = pair ? "sphere-sphere" : "sphere-wall";
  j["vary"] = sw.vary;
  j["table"] = "dem.csv";
  j["lookup_table"] = "dem_table.csv";
  j["St_convention"] = kStConvention;
  j["St_column"] = pair ? "St_B_eq_6_2" : "St";
  j["e_dry_scene"] = sw.e_dry ? nlohmann::ordered_json(*sw.e_dry) : nlohmann::ordered_json(nullptr);
  std::size_t used = 0, no_rebound = 0, without_e = 0;
  double St_no_rebound_max = 0;
  for (const auto& s : samples) {
    if (!s.e) ++without_e;
    else if (*s.e > 0) ++used;
    else ++no_rebound, St_no_rebound_max = std::max(St_no_rebound_max, s.St);
  }
  j["points"] = {{"total", pts.size()}, {"used_in_fits", used}, {"no_rebound", no_rebound}, {"without_e", without_e}, {"without_St", without_St}};
  j["St_no_rebound_max"] = no_rebound ? nlohmann::ordered_json(St_no_rebound_max) : nlohmann::ordered_json(nullptr);
  j["treatment"] = "points with e = 0 (no rebound), points without e (failed runs, e not measured) and points with e but without St (no "
                   "liquid) are left out of the fits and counted here; the fits hold over valid_St, the St range of the points used";
  j["tolerance_max_residual"] = kDemFitTolerance;
  j["fits"] = nlohmann::ordered_json::array();
  for (const auto& f : fits) j["fits"].push_back(fit_json(f, pair));

  // The best fit: the smallest rms residual among those with e_dry free (with e_dry fixed when none is free), of the
  // fits whose e_dry is a restitution (<= 1).
  const RestitutionFit* best = nullptr;
  for (const auto& f : fits)
    if (f.e_dry <= 1 &&
        (!best || (f.e_dry_free && !best->e_dry_free) || (f.e_dry_free == best->e_dry_free && f.rms_residual < best->rms_residual)))
      best = &f;
  const RestitutionFit* expo = nullptr;  // the exponential fit (e_dry free if <= 1): the form of LIGGGHTS's viscous model
  for (const auto& f : fits)
    if (f.form == RestitutionForm::exponential && (!expo || (f.e_dry_free && f.e_dry <= 1))) expo = &f;
  auto which = [](const RestitutionFit* f) {
    return f ? nlohmann::ordered_json{{"form", to_string(f->form)}, {"e_dry_is", f->e_dry_free ? "fitted" : "fixed to the scene's"}}
             : nlohmann::ordered_json(nullptr);
  };
  j["best"] = which(best);
  j["exp"] = which(expo);
  j["fit_error"] = fit_error.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(fit_error);
  write_file_atomic(dir / "dem.json", j.dump(2) + "\n");

  if (!best) {
    std::string line = "dem: no fit: " + fit_error;
    if (without_St) {  // what the points found instead: e without St
      double lo = INFINITY, hi = -INFINITY;
      for (const auto& p : pts)
        if (p.e && !dem_St(p, pair)) lo = std::min(lo, *p.e), hi = std::max(hi, *p.e);
      const std::string a = fixed(lo, 4), b = fixed(hi, 4);
      line += "; e = " + (a == b ? a : a + "-" + b) + " at " + std::to_string(without_St) + " of " +
              std::to_string(pts.size()) + " points";
    }
    return line;
  }
  std::ostringstream os;
  os << "dem: " << fit_text(*best) << ", St " << fixed(best->St_min, 1) << "-" << fixed(best->St_max, 1) << " (" << best->used << " points)";
  if (expo && expo != best) os << "; " << fit_text(*expo);
  return os.str();
}

}  // namespace imcol
