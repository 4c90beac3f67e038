// SPDX-License-Identifier: BSD-3-Clause
// imcol.laws: the solid contact laws compared on one scene, or over a sweep of one quantity, as `imcol laws` runs
// them (study/laws.hpp), the GIL released while they run; laws.csv's columns as an imcol.StudyTable.
#include <pybind11/stl.h>

#include <optional>

#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/call.hpp"
#include "python/interrupt.hpp"
#include "python/convert.hpp"
#include "python/scene.hpp"
#include "python/table.hpp"
#include "study/laws.hpp"

namespace py = pybind11;

namespace imcol::python {

namespace laws_impl {  // this file's helpers: named, as the module is one unity unit

/// What laws.json says besides the rows: e's measure, the contact's e_dry and delta_SS, the laws and the sweep.
py::dict laws_info(const study::LawsResult& r) {
  nlohmann::ordered_json j;
  j["e_is"] = r.e_is;
  j["e_dry"] = r.contact ? nlohmann::ordered_json(r.contact->e_dry) : nlohmann::ordered_json(nullptr);
  j["delta_ss_m"] = r.contact ? nlohmann::ordered_json(r.contact->delta_ss_m) : nlohmann::ordered_json(nullptr);
  j["laws"] = r.laws;
  j["vary"] = r.vary.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.vary);
  j["column"] = r.column.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.column);
  j["cancelled"] = r.cancelled;
  return to_python(j);
}

PyTable laws(const py::object& scene_arg, const std::optional<std::vector<std::string>>& names, const std::optional<std::string>& vary,
             const std::optional<std::vector<double>>& values, const std::optional<py::object>& rtol, const std::optional<py::object>& atol,
             const std::optional<std::string>& integrator, const py::object& progress) {
  require_numpy("imcol.laws");
  check_progress_callable(progress, "imcol.laws");
  const PyScene scene = scene_argument(scene_arg, "imcol.laws").cast<PyScene>();
  const std::vector<std::string> chosen = study::laws_to_compare(names.value_or(std::vector<std::string>{}), "imcol.laws", "laws");
  if (vary) {
    study::check_sweep_quantity(*vary, "imcol.laws", "vary");
    if (!values) throw InputError("imcol.laws", "values", "missing: give the values of " + *vary + " (SI units)");
    study::check_sweep_values(*vary, *values, "imcol.laws", "values");
  } else if (values) {
    throw InputError("imcol.laws", "values", "needs vary: the quantity the values are of");
  }
  std::vector<Override> overrides = scene.overrides();
  for (auto& o : solver_overrides(rtol, atol, integrator)) overrides.push_back(o);
  const auto load = [&](const std::vector<Override>& ov) { return parse_scene(scene.text(), scene.path(), ov); };
  study::LawsResult r;
  call_interruptibly(  // the runs touch no Python object
      [&] { r = study::compare_laws(load, overrides, chosen, vary.value_or(""), values.value_or(std::vector<double>{}), false, interruptible_hooks()); },
      progress);
  return make_table("laws", study::laws_table(r), laws_info(r));
}

}  // namespace laws_impl

void bind_laws(py::module_& m) {
  m.def("laws", in_call("imcol.laws", &laws_impl::laws), py::arg("scene"), py::arg("laws") = py::none(), py::arg("vary") = py::none(),
        py::arg("values") = py::none(), py::arg("rtol") = py::none(), py::arg("atol") = py::none(), py::arg("integrator") = py::none(),
        py::arg("progress") = py::none(),
        "Runs a scene (an imcol.Scene, a shipped scene's name or a scene file's path) once per contact law (`laws`, default every shipped law: "
        "imcol.contact_laws()) as `imcol laws` does; with `vary` and `values`, at each value of that quantity "
        "(imcol.sweep_quantities()). The runs go one after the other, the GIL released; Ctrl-C stops the run in flight within a step "
        "(KeyboardInterrupt). progress: None or progress(done, total, eta_s), runs finished of all. A law that refuses the scene "
        "or fails gets a row saying why. Returns an imcol.StudyTable: laws.csv's columns (info: e_is, e_dry, "
        "delta_ss_m, laws, vary, column).");
}

}  // namespace imcol::python
