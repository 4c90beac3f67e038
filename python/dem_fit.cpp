// SPDX-License-Identifier: BSD-3-Clause
// imcol.dem_fit: a sweep's e against St in the shape a DEM code reads and the fits of e = e_dry f(St_c/St)
// (study/dem_fit.hpp), as `imcol sweep … --export dem` writes dem.csv and dem.json.
#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "python/call.hpp"
#include "python/convert.hpp"
#include "python/sweep.hpp"
#include "python/table.hpp"
#include "study/dem_fit.hpp"
#include "study/dem_liggghts.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace dem_impl {  // this file's helpers: named, as the module is one unity unit

/// The scene's dry restitution as sweep.json has it: the first point that ran, when the scene has a contact.
std::optional<double> sweep_e_dry(const study::SweepResult& r) {
  for (const auto& p : r.points)
    if (p.ok) return p.summary.contact ? std::optional<double>(p.summary.contact->e_dry) : std::nullopt;
  return std::nullopt;
}

/// What dem.json says besides the table: the points' counts, every fit, the best and the exponential one.
nlohmann::ordered_json dem_info(const study::DemFit& f, std::optional<double> e_dry, const study::LiggghtsExport& lx) {
  using J = nlohmann::ordered_json;
  J j;
  j["St_convention"] = study::kDemStConvention;
  j["St_column"] = f.pair ? "St_B_eq_6_2" : "St";
  j["e_dry_scene"] = e_dry ? J(*e_dry) : J(nullptr);
  j["points"] = {{"total", f.total}, {"used_in_fits", f.used}, {"no_rebound", f.no_rebound}, {"without_e", f.without_e}, {"without_St", f.without_St}};
  j["St_no_rebound_max"] = f.St_no_rebound_max ? J(*f.St_no_rebound_max) : J(nullptr);
  j["fits"] = J::array();
  for (const auto& x : f.fits) j["fits"].push_back(study::dem_fit_json(x, f.pair));
  j["best"] = f.best < 0 ? J(nullptr) : j["fits"][static_cast<std::size_t>(f.best)];
  j["exp"] = f.exp < 0 ? J(nullptr) : j["fits"][static_cast<std::size_t>(f.exp)];
  j["fit_error"] = f.fit_error.empty() ? J(nullptr) : J(f.fit_error);
  j["liggghts"] = study::liggghts_json(lx);
  return j;
}

PyTable dem_fit(const PySweepResult& sweep) {
  const std::optional<double> e_dry = sweep_e_dry(sweep.result);
  const std::vector<study::DemPoint> pts = study::dem_points(sweep.result);
  study::DemFit f;
  study::LiggghtsExport lx;
  {
    py::gil_scoped_release free;
    f = study::fit_dem(pts, e_dry, sweep.liquid, sweep.pair);
    lx = study::liggghts_export(sweep.base, pts, f, e_dry);
  }
  return make_table("dem", study::dem_table(pts, sweep.column, e_dry, sweep.pair), to_python(dem_info(f, e_dry, lx)));
}

}  // namespace dem_impl

void bind_dem_fit(py::module_& m) {
  m.def("dem_fit", in_call("imcol.dem_fit", &dem_impl::dem_fit), py::arg("sweep"),
        "A sweep's points (an imcol.SweepResult) as `imcol sweep … --export dem` writes them: an imcol.StudyTable of "
        "dem.csv's columns (St in the DEM convention, m* U / (6 pi mu a*^2)), and in `info` dem.json's fits of "
        "e = e_dry f(St_c/St), exp and linear, e_dry fixed to the scene's and free (`fits`, `best`, `exp`, `fit_error`, "
        "`points`), and LIGGGHTS's hooke viscous rule fitted through a replay of its normal force (`liggghts`: "
        "CriticalStokes, MaximumRestitution, the replay's residual).");
}

}  // namespace imcol::python
