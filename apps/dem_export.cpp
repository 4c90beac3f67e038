// SPDX-License-Identifier: BSD-3-Clause
#include "apps/dem_export.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "apps/format.hpp"
#include "core/report.hpp"
#include "apps/table_csv.hpp"
#include "run/restitution_fit.hpp"
#include "study/dem_liggghts.hpp"

namespace imcol {

namespace fs = std::filesystem;
using run::RestitutionFit;
using study::dem_St;
using study::DemFit;
using study::kDemFitTolerance;

namespace {

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
    os << "# St = St_B_table_6_1 (imcol's pair convention, half of eq. 6.2); St_B_eq_6_2 = " << study::kDemStConvention << " (the DEM convention)\n";
  else
    os << "# St = " << study::kDemStConvention << " (the DEM convention)\n";
  os << "# units: " << sw.column << " SI; impact_speed_m_s m/s (approach speed at contact, from the fitted approach line); St, e, "
        "e_over_e_dry dimensionless; status ok | failed; e_status measured | measures_disagree | not_measured; used_in_fit 1 if e > 0\n";
  return os.str();
}

std::string dem_csv(const Scene& base, const DemSweep& sw, const std::vector<DemPoint>& pts, bool pair) {
  return csv_comment(base, sw, pair) + table_csv(study::dem_table(pts, sw.column, sw.e_dry, pair));
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

std::string fit_text(const RestitutionFit& f) {
  std::ostringstream os;
  os << formula(f.form) << ": St_c = " << fixed(f.St_c, 2) << ", e_dry = " << fixed(f.e_dry, 3) << (f.e_dry_free ? "" : " (fixed)")
     << ", residual in e rms " << fixed(f.rms_residual, 4) << " max " << fixed(f.max_residual, 4)
     << (f.max_residual <= kDemFitTolerance ? "" : " (beyond " + fixed(kDemFitTolerance, 2) + ": the form does not fit)");
  return os.str();
}

/// dem.json: the scene, the points' counts, every fit and which is best.
nlohmann::ordered_json dem_json(const Scene& base, const DemSweep& sw, const DemFit& f, const study::LiggghtsExport& lx) {
  nlohmann::ordered_json j;
  j["scene"] = base.name;
  j["scene_file"] = sw.scene_file;
  j["configuration"] = f.pair ? "sphere-sphere" : "sphere-wall";
  j["vary"] = sw.vary;
  j["table"] = "dem.csv";
  j["lookup_table"] = "dem_table.csv";
  j["St_convention"] = study::kDemStConvention;
  j["St_column"] = f.pair ? "St_B_eq_6_2" : "St";
  j["e_dry_scene"] = sw.e_dry ? nlohmann::ordered_json(*sw.e_dry) : nlohmann::ordered_json(nullptr);
  j["points"] = {{"total", f.total}, {"used_in_fits", f.used}, {"no_rebound", f.no_rebound}, {"without_e", f.without_e}, {"without_St", f.without_St}};
  j["St_no_rebound_max"] = f.St_no_rebound_max ? nlohmann::ordered_json(*f.St_no_rebound_max) : nlohmann::ordered_json(nullptr);
  j["treatment"] = "points with e = 0 (no rebound), points without e (failed runs, e not measured) and points with e but without St (no "
                   "liquid) are left out of the fits and counted here; the fits hold over valid_St, the St range of the points used";
  j["tolerance_max_residual"] = kDemFitTolerance;
  j["fits"] = nlohmann::ordered_json::array();
  for (const auto& x : f.fits) j["fits"].push_back(study::dem_fit_json(x, f.pair));
  auto which = [&](int k) {
    if (k < 0) return nlohmann::ordered_json(nullptr);
    const RestitutionFit& x = f.fits[static_cast<std::size_t>(k)];
    return nlohmann::ordered_json{{"form", to_string(x.form)}, {"e_dry_is", x.e_dry_free ? "fitted" : "fixed to the scene's"}};
  };
  j["best"] = which(f.best);
  j["exp"] = which(f.exp);
  j["fit_error"] = f.fit_error.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(f.fit_error);
  j["liggghts"] = study::liggghts_json(lx);
  return j;
}

/// The terminal's line: the best fit, the exponential one and LIGGGHTS's rule fitted through the replay, or why
/// there is none.
std::string dem_line(const DemFit& f, const std::vector<DemPoint>& pts, const study::LiggghtsExport& lx) {
  if (f.best < 0) {
    std::string line = "dem: no fit: " + f.fit_error;
    if (f.without_St) {  // what the points found instead: e without St
      double lo = INFINITY, hi = -INFINITY;
      for (const auto& p : pts)
        if (p.e && !dem_St(p, f.pair)) lo = std::min(lo, *p.e), hi = std::max(hi, *p.e);
      const std::string a = fixed(lo, 4), b = fixed(hi, 4);
      line += "; e = " + (a == b ? a : a + "-" + b) + " at " + std::to_string(f.without_St) + " of " + std::to_string(pts.size()) + " points";
    }
    return line;
  }
  const RestitutionFit& best = f.fits[static_cast<std::size_t>(f.best)];
  std::ostringstream os;
  os << "dem: " << fit_text(best) << ", St " << fixed(best.St_min, 1) << "-" << fixed(best.St_max, 1) << " (" << best.used << " points)";
  if (f.exp >= 0 && f.exp != f.best) os << "; " << fit_text(f.fits[static_cast<std::size_t>(f.exp)]);
  os << "; " << study::liggghts_text(lx);
  return os.str();
}

}  // namespace

std::string export_dem(const fs::path& dir, const Scene& base, const DemSweep& sw, const std::vector<DemPoint>& pts) {
  const bool pair = base.spheres.size() == 2;
  write_file_atomic(dir / "dem.csv", dem_csv(base, sw, pts, pair));
  write_file_atomic(dir / "dem_table.csv", lookup_csv(sw, pts, pair));
  const DemFit f = study::fit_dem(pts, sw.e_dry, base.fluid.has_value(), pair);
  const study::LiggghtsExport lx = study::liggghts_export(base, pts, f, sw.e_dry);
  write_file_atomic(dir / "dem.json", dem_json(base, sw, f, lx).dump(2) + "\n");
  return dem_line(f, pts, lx);
}

}  // namespace imcol
